// YAML scene files: a scene written as matrices of muParser expressions in t, pi and the
// scene's parameters (see scenes/*.yaml for commented examples).
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "expression.h"
#include "expression_matrix.h"
#include "ltp/core/bounded_coefficients.h"
#include "ltp/core/error.h"
#include "ltp/core/periodic_coefficients.h"
#include "ltp/core/second_order.h"
#include "ltp/core/text.h"
#include "ltp/models/scene.h"
#include "matrix_market.h"
#include "npz.h"
#include "scene_file_matrices.h"

namespace ltp {
namespace {

using internal::ExpressionEntry;
using internal::ExpressionMatrixText;

// What a scene file says, kept with the location of every entry so that errors found when the
// scene is built (after --set overrides) still name the file, line and entry.
struct SceneModel {
  std::optional<ExpressionEntry> period, omega, rotor_speed;
  std::vector<ExpressionEntry> breakpoints;
  bool second_order = false;
  std::string mass_where;  // location of second_order.M, for SingularMassError
  // state_space: A, B, C, D.  second_order: M, D, K, F, Cd, Cv. Absent matrices are empty.
  std::map<std::string, ExpressionMatrixText> matrices;
  // second_order matrices given as Matrix Market files instead (the scene is then Fourier form).
  std::map<std::string, internal::FileMatrix> file_matrices;
  int states = 0, inputs = 0, outputs = 0;
  SystemLabels labels;
  // sampled: matrices at K times (or azimuths) over one period. Each of A, B, C, D holds K
  // matrices, or one (constant) matrix; absent B, C, D hold none.
  bool sampled = false;
  bool fourier_interpolation = false;
  std::string sampled_where;  // location of the sampled block, for messages at build time
  std::vector<ExpressionEntry> sample_points;
  bool points_are_azimuths = false;
  std::map<std::string, std::vector<ExpressionMatrixText>> sample_matrices;
};

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  // "file:line: entry", the prefix of every message about `node`.
  std::string Where(const YAML::Node& node, const std::string& entry) const {
    return Where(node.Mark(), entry);
  }
  std::string Where(const YAML::Mark& mark, const std::string& entry) const {
    std::string where = source_;
    if (mark.line >= 0) where.append(":").append(std::to_string(mark.line + 1));
    if (!entry.empty()) where.append(": ").append(entry);
    return where;
  }
  [[noreturn]] void Fail(const YAML::Node& node, const std::string& entry,
                         const std::string& message) const {
    Fail(node.Mark(), entry, message);
  }
  [[noreturn]] void Fail(const YAML::Mark& mark, const std::string& entry,
                         const std::string& message) const {
    throw SceneError(Where(mark, entry) + ": " + message);
  }

  // Where `key` of the mapping `map` is written (a block's own mark is its first entry's).
  static YAML::Mark KeyMark(const YAML::Node& map, const std::string& key) {
    for (const auto& item : map)
      if (item.first.Scalar() == key) return item.first.Mark();
    return map.Mark();
  }

  std::string Scalar(const YAML::Node& node, const std::string& entry) const {
    if (!node.IsScalar()) Fail(node, entry, "expected a number or an expression");
    return node.Scalar();
  }
  ExpressionEntry Expression(const YAML::Node& node, const std::string& entry) const {
    return {Scalar(node, entry), Where(node, entry)};
  }
  std::vector<std::string> Names(const YAML::Node& node, const std::string& entry) const {
    if (!node.IsSequence()) Fail(node, entry, "expected a list of names, e.g. [x, y]");
    std::vector<std::string> names;
    for (size_t i = 0; i < node.size(); ++i)
      names.push_back(Scalar(node[i], entry + "[" + std::to_string(i) + "]"));
    return names;
  }

  // A non-empty list of equally long rows of expressions.
  ExpressionMatrixText Matrix(const YAML::Node& node, const std::string& entry) const {
    if (!node.IsSequence() || node.size() == 0)
      Fail(node, entry,
           "expected a matrix: a list of rows, e.g. [[\"0\", \"1\"], [\"-k\", \"0\"]]");
    // A scene file's matrices are written out entry by entry; YAML aliases can make a short file
    // describe millions of entries (5000 × 5000 zeros in 30 KB), each an expression to compile.
    // Larger systems come as OpenFAST .lin sets or Fourier data, not hand-written scenes.
    constexpr size_t kMaxDimension = 1000;
    if (node.size() > kMaxDimension || (node[0].IsSequence() && node[0].size() > kMaxDimension))
      Fail(node, entry,
           "matrix larger than " + std::to_string(kMaxDimension) + " rows or columns (" +
               std::to_string(node.size()) + " rows): the limit for expression scenes");
    ExpressionMatrixText rows;
    for (size_t r = 0; r < node.size(); ++r) {
      const YAML::Node row = node[r];
      const std::string row_entry = entry + "[" + std::to_string(r) + "]";
      if (!row.IsSequence() || row.size() == 0)
        Fail(row, row_entry, "expected a row: a list of entries, e.g. [\"0\", \"1\"]");
      if (r > 0 && row.size() != rows[0].size())
        Fail(row, row_entry,
             "row has " + std::to_string(row.size()) + " entries but row 0 has " +
                 std::to_string(rows[0].size()));
      rows.emplace_back();
      for (size_t c = 0; c < row.size(); ++c)
        rows.back().push_back(Expression(row[c], row_entry + "[" + std::to_string(c) + "]"));
    }
    return rows;
  }

  // A matrix from Matrix Market files: one term {file, factor, harmonics} or a list of them,
  // file names relative to the scene file's directory.
  internal::FileMatrix FileMatrix(const YAML::Node& node, const std::string& entry) const {
    internal::FileMatrix m;
    m.where = Where(node, entry);
    if (node.IsMap()) {
      m.terms.push_back(FileTerm(node, entry, m));
    } else {
      for (size_t i = 0; i < node.size(); ++i)
        m.terms.push_back(FileTerm(node[i], entry + "[" + std::to_string(i) + "]", m));
    }
    return m;
  }

  void CheckKeys(const YAML::Node& map, const std::string& entry,
                 const std::set<std::string>& allowed) const {
    for (const auto& item : map) {
      const std::string key = item.first.Scalar();
      if (allowed.count(key) > 0) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      Fail(item.first, entry.empty() ? key : entry + "." + key,
           "unknown key (expected one of: " + list + ")");
    }
  }

  const std::string& source() const { return source_; }

 private:
  internal::FileMatrixTerm FileTerm(const YAML::Node& node, const std::string& entry,
                                    internal::FileMatrix& m) const {
    if (!node.IsMap()) Fail(node, entry, "expected {file: M.mtx, factor: ..., harmonics: [...]}");
    CheckKeys(node, entry, {"file", "factor", "harmonics"});
    internal::FileMatrixTerm term;
    if (node["file"]) term.constant = MatrixFile(node["file"], entry + ".file", m);
    if (node["factor"]) term.factor = Expression(node["factor"], entry + ".factor");
    if (const YAML::Node harmonics = node["harmonics"]) {
      if (!harmonics.IsSequence())
        Fail(harmonics, entry + ".harmonics", "expected a list of {order, cos, sin}");
      for (size_t i = 0; i < harmonics.size(); ++i) {
        const YAML::Node h = harmonics[i];
        const std::string at = entry + ".harmonics[" + std::to_string(i) + "]";
        if (!h.IsMap()) Fail(h, at, "expected {order: 1, cos: C.mtx, sin: S.mtx}");
        CheckKeys(h, at, {"order", "cos", "sin"});
        internal::FileMatrixTerm::Harmonic harmonic;
        if (h["order"]) {
          const std::string order = Scalar(h["order"], at + ".order");
          const bool digits = !order.empty() && order.size() <= 3 &&
                              order.find_first_not_of("0123456789") == std::string::npos;
          harmonic.order = digits ? std::stoi(order) : 0;
          if (harmonic.order < 1)
            Fail(h["order"], at + ".order", "expected an integer 1..999, got '" + order + "'");
        }
        if (h["cos"]) harmonic.cos = MatrixFile(h["cos"], at + ".cos", m);
        if (h["sin"]) harmonic.sin = MatrixFile(h["sin"], at + ".sin", m);
        if (!h["cos"] && !h["sin"]) Fail(h, at, "gives neither cos nor sin");
        term.harmonics.push_back(std::move(harmonic));
      }
    }
    if (!node["file"] && !node["harmonics"]) Fail(node, entry, "gives neither file nor harmonics");
    return term;
  }

  // Reads one .mtx file, or one array of a .npz archive ("model.npz:K"); every file of a
  // matrix must have the same size.
  Eigen::MatrixXd MatrixFile(const YAML::Node& node, const std::string& entry,
                             internal::FileMatrix& m) const {
    const std::string name = Scalar(node, entry);
    const size_t npz = name.rfind(".npz:");
    std::filesystem::path path(npz == std::string::npos ? name : name.substr(0, npz + 4));
    if (path.is_relative()) path = std::filesystem::path(source_).parent_path() / path;
    if (npz == std::string::npos && path.extension() == ".npz")
      Fail(node, entry, "name the array in the archive: " + name + ":K");
    Eigen::MatrixXd a;
    try {
      a = npz != std::string::npos ? internal::ReadNpzArray(path.string(), name.substr(npz + 5))
                                   : internal::ReadMatrixMarket(path.string());
    } catch (const SceneError& e) {
      Fail(node, entry, e.what());
    }
    if (m.rows == 0) {
      m.rows = static_cast<int>(a.rows());
      m.cols = static_cast<int>(a.cols());
    } else if (a.rows() != m.rows || a.cols() != m.cols) {
      Fail(node, entry,
           name + " is " + std::to_string(a.rows()) + "x" + std::to_string(a.cols()) +
               " but the matrix's other files are " + std::to_string(m.rows) + "x" +
               std::to_string(m.cols));
    }
    return a;
  }

  std::string source_;
};

int Rows(const ExpressionMatrixText& m) { return static_cast<int>(m.size()); }
int Cols(const ExpressionMatrixText& m) { return m.empty() ? 0 : static_cast<int>(m[0].size()); }

std::string Size(const ExpressionMatrixText& m) {
  return std::to_string(Rows(m)) + "x" + std::to_string(Cols(m));
}

// A matrix given as Matrix Market file terms ({file: ...} or a list of them), not expressions.
bool FromFiles(const YAML::Node& node) {
  return node.IsMap() || (node.IsSequence() && node.size() > 0 && node[0].IsMap());
}

// Rows and columns of matrix `name` of the model, from expressions or files.
std::pair<int, int> SizeOf(const SceneModel& model, const std::string& name) {
  if (const auto f = model.file_matrices.find(name); f != model.file_matrices.end())
    return {f->second.rows, f->second.cols};
  const auto e = model.matrices.find(name);
  if (e == model.matrices.end()) return {0, 0};
  return {Rows(e->second), Cols(e->second)};
}

// Reads an optional matrix `key` of `block` and checks its size (-1: any).
void ReadMatrix(const Reader& reader, const YAML::Node& block, const std::string& block_name,
                const std::string& key, const std::string& stored_as, int rows, int cols,
                SceneModel& model) {
  const YAML::Node node = block[key];
  if (!node) return;
  const std::string entry = block_name + "." + key;
  if (FromFiles(node)) {
    if (!model.second_order)
      reader.Fail(node, entry, "matrices from files are read in a second_order block only");
    model.file_matrices[stored_as] = reader.FileMatrix(node, entry);
  } else {
    model.matrices[stored_as] = reader.Matrix(node, entry);
  }
  const auto [r, c] = SizeOf(model, stored_as);
  if ((rows >= 0 && r != rows) || (cols >= 0 && c != cols))
    reader.Fail(node, entry,
                "is " + std::to_string(r) + "x" + std::to_string(c) + " but must be " +
                    (rows >= 0 ? std::to_string(rows) : "any") + "x" +
                    (cols >= 0 ? std::to_string(cols) : "any"));
}

void ReadStateSpace(const Reader& reader, const YAML::Node& root, SceneModel& model) {
  const std::string name = "state_space";
  const YAML::Node block = root[name];
  const YAML::Mark mark = Reader::KeyMark(root, name);
  if (!block.IsMap()) reader.Fail(mark, name, "expected a mapping with A and optional B, C, D");
  reader.CheckKeys(block, name, {"A", "B", "C", "D"});
  if (!block["A"]) reader.Fail(mark, name, "missing the state matrix A");
  const ExpressionMatrixText a = reader.Matrix(block["A"], name + ".A");
  if (Rows(a) != Cols(a)) reader.Fail(block["A"], name + ".A", "must be square, got " + Size(a));
  const int n = Rows(a);
  model.matrices["A"] = a;
  ReadMatrix(reader, block, name, "B", "B", n, -1, model);
  ReadMatrix(reader, block, name, "C", "C", -1, n, model);
  model.states = n;
  model.inputs = Cols(model.matrices["B"]);
  model.outputs = Rows(model.matrices["C"]);
  if (block["D"] && (model.inputs == 0 || model.outputs == 0))
    reader.Fail(block["D"], name + ".D", "feedthrough D needs both B and C");
  ReadMatrix(reader, block, name, "D", "D", model.outputs, model.inputs, model);
}

void ReadSecondOrder(const Reader& reader, const YAML::Node& root, SceneModel& model) {
  const std::string name = "second_order";
  const YAML::Node block = root[name];
  const YAML::Mark mark = Reader::KeyMark(root, name);
  if (!block.IsMap())
    reader.Fail(mark, name, "expected a mapping with M, K and optional D, F, outputs");
  reader.CheckKeys(block, name, {"M", "D", "K", "F", "outputs"});
  if (!block["M"]) reader.Fail(mark, name, "missing the mass matrix M");
  if (!block["K"]) reader.Fail(mark, name, "missing the stiffness matrix K");
  ReadMatrix(reader, block, name, "M", "M", -1, -1, model);
  const auto [q, mass_cols] = SizeOf(model, "M");
  if (q != mass_cols)
    reader.Fail(block["M"], name + ".M",
                "must be square, got " + std::to_string(q) + "x" + std::to_string(mass_cols));
  model.mass_where = reader.Where(block["M"], name + ".M");
  ReadMatrix(reader, block, name, "K", "K", q, q, model);
  ReadMatrix(reader, block, name, "D", "D", q, q, model);
  ReadMatrix(reader, block, name, "F", "F", q, -1, model);
  model.states = 2 * q;
  model.inputs = SizeOf(model, "F").second;
  if (const YAML::Node outputs = block["outputs"]) {
    const std::string entry = name + ".outputs";
    if (!outputs.IsMap())
      reader.Fail(outputs, entry, "expected a mapping with displacement and/or velocity");
    reader.CheckKeys(outputs, entry, {"displacement", "velocity"});
    ReadMatrix(reader, outputs, entry, "displacement", "Cd", -1, q, model);
    const int p = SizeOf(model, "Cd").first;
    ReadMatrix(reader, outputs, entry, "velocity", "Cv", p > 0 ? p : -1, q, model);
    model.outputs = std::max(p, SizeOf(model, "Cv").first);
  }
}

// sampled: {times: [...] | azimuths_deg: [...], interpolation: constant|fourier,
//           A: [A_1, ..., A_K], B, C, D: K matrices or one constant matrix}.
void ReadSampled(const Reader& reader, const YAML::Node& root, SceneModel& model) {
  const std::string name = "sampled";
  const YAML::Node block = root[name];
  const YAML::Mark mark = Reader::KeyMark(root, name);
  if (!block.IsMap())
    reader.Fail(mark, name,
                "expected a mapping with times (or azimuths_deg), interpolation and A, B, C, D");
  reader.CheckKeys(block, name, {"times", "azimuths_deg", "interpolation", "A", "B", "C", "D"});
  model.sampled = true;
  model.sampled_where = reader.Where(mark, name);
  if (block["times"] && block["azimuths_deg"])
    reader.Fail(block["azimuths_deg"], name + ".azimuths_deg",
                "give either times or azimuths_deg, not both");
  const std::string points_key = block["times"] ? "times" : "azimuths_deg";
  const YAML::Node points = block[points_key];
  if (!points) reader.Fail(mark, name, "missing the sample times (times or azimuths_deg)");
  if (!points.IsSequence() || points.size() == 0)
    reader.Fail(points, name + "." + points_key, "expected a non-empty list of numbers");
  model.points_are_azimuths = points_key == "azimuths_deg";
  for (size_t k = 0; k < points.size(); ++k)
    model.sample_points.push_back(
        reader.Expression(points[k], name + "." + points_key + "[" + std::to_string(k) + "]"));
  const int samples = static_cast<int>(points.size());

  if (!block["interpolation"])
    reader.Fail(mark, name, "missing 'interpolation' (constant or fourier)");
  const std::string interpolation = reader.Scalar(block["interpolation"], name + ".interpolation");
  if (interpolation != "constant" && interpolation != "fourier")
    reader.Fail(block["interpolation"], name + ".interpolation",
                "must be 'constant' (held between samples) or 'fourier' (trigonometric), got '" +
                    interpolation + "'");
  model.fourier_interpolation = interpolation == "fourier";

  if (!block["A"]) reader.Fail(mark, name, "missing the state matrices A");
  // Reads K matrices (or one, when `constant_allowed`), all of the size of the first.
  auto read = [&](const std::string& key, bool constant_allowed, int rows, int cols) {
    const YAML::Node node = block[key];
    if (!node) return;
    const std::string entry = name + "." + key;
    const bool one_matrix = node.IsSequence() && node.size() > 0 && node[0].IsSequence() &&
                            node[0].size() > 0 && !node[0][0].IsSequence();
    std::vector<ExpressionMatrixText> matrices;
    if (one_matrix) {
      if (!constant_allowed)
        reader.Fail(node, entry,
                    "expected one matrix per sample (" + std::to_string(samples) +
                        "), e.g. [[[0, 1], [-1, 0]], ...]");
      matrices.push_back(reader.Matrix(node, entry));
    } else {
      if (!node.IsSequence() || static_cast<int>(node.size()) != samples)
        reader.Fail(node, entry,
                    "expected " + std::to_string(samples) + " matrices (one per sample" +
                        (constant_allowed ? ") or one constant matrix" : ")"));
      for (int k = 0; k < samples; ++k)
        matrices.push_back(reader.Matrix(node[k], entry + "[" + std::to_string(k) + "]"));
    }
    for (size_t k = 0; k < matrices.size(); ++k) {
      const int want_rows = rows >= 0 ? rows : Rows(matrices[0]);
      const int want_cols = cols >= 0 ? cols : Cols(matrices[0]);
      if (Rows(matrices[k]) != want_rows || Cols(matrices[k]) != want_cols)
        reader.Fail(one_matrix ? node : node[k], entry,
                    "is " + Size(matrices[k]) + " but must be " + std::to_string(want_rows) + "x" +
                        std::to_string(want_cols));
    }
    model.sample_matrices[key] = std::move(matrices);
  };
  read("A", false, -1, -1);
  const ExpressionMatrixText& a0 = model.sample_matrices["A"][0];
  if (Rows(a0) != Cols(a0)) reader.Fail(block["A"], name + ".A", "must be square, got " + Size(a0));
  const int n = Rows(a0);
  read("B", true, n, -1);
  read("C", true, -1, n);
  model.states = n;
  const auto& b = model.sample_matrices["B"];
  const auto& c = model.sample_matrices["C"];
  model.inputs = b.empty() ? 0 : Cols(b[0]);
  model.outputs = c.empty() ? 0 : Rows(c[0]);
  if (block["D"] && (model.inputs == 0 || model.outputs == 0))
    reader.Fail(block["D"], name + ".D", "feedthrough D needs both B and C");
  read("D", true, model.outputs, model.inputs);
}

void CheckLabels(const Reader& reader, const YAML::Node& root, const std::string& key,
                 std::vector<std::string>& names, int count) {
  const YAML::Node node = root[key];
  if (!node) return;
  names = reader.Names(node, key);
  if (static_cast<int>(names.size()) != count)
    reader.Fail(node, key,
                "gives " + std::to_string(names.size()) + " names but the system has " +
                    std::to_string(count) + " " + key);
}

// whirl_pairs: [[x, y], ...] by state name (the rotor turning from x towards y).
void ReadWhirlPairs(const Reader& reader, const YAML::Node& root, SystemLabels& labels) {
  const YAML::Node node = root["whirl_pairs"];
  if (!node) return;
  const std::string hint = "expected a list of [x, y] state-name pairs, e.g. [[x, y]]";
  if (!node.IsSequence()) reader.Fail(node, "whirl_pairs", hint);
  for (size_t i = 0; i < node.size(); ++i) {
    const std::string entry = "whirl_pairs[" + std::to_string(i) + "]";
    if (!node[i].IsSequence() || node[i].size() != 2) reader.Fail(node[i], entry, hint);
    std::array<int, 2> pair{};
    for (size_t c = 0; c < 2; ++c) {
      if (!node[i][c].IsScalar()) reader.Fail(node[i][c], entry, hint);
      const std::string name = node[i][c].Scalar();
      const auto it = std::find(labels.states.begin(), labels.states.end(), name);
      if (it == labels.states.end())
        reader.Fail(node[i][c], entry, "'" + name + "' is not one of the scene's states");
      pair[c] = static_cast<int>(it - labels.states.begin());
    }
    if (pair[0] == pair[1]) reader.Fail(node[i], entry, "x and y must be different states");
    labels.whirl_pairs.push_back(pair);
  }
}

// Evaluates a constant expression in pi and the parameters. @throws SceneError.
double Value(const ExpressionEntry& entry, const internal::Constants& constants) {
  double value = 0;
  try {
    value = internal::EvaluateConstant(entry.text, constants);
  } catch (const internal::ExpressionError& e) {
    throw SceneError(entry.where + ": " + e.what());
  }
  if (!std::isfinite(value))
    throw SceneError(entry.where + ": '" + entry.text + "' evaluates to " +
                     internal::FormatValue(value));
  return value;
}

// Explicit breakpoints first (they are exact), then detected jumps not already listed.
std::vector<double> MergeBreakpoints(std::vector<double> explicit_times,
                                     const std::vector<double>& found, double period) {
  const double tolerance = 1e-9 * period;
  std::vector<double> all = std::move(explicit_times);
  for (double t : found) {
    const bool known = std::any_of(all.begin(), all.end(), [&](double b) {
      const double d = std::abs(b - t);
      return d < tolerance || period - d < tolerance;
    });
    if (!known) all.push_back(t);
  }
  std::sort(all.begin(), all.end());
  return all;
}

// The sampled system: piecewise constant (exact product of exponentials) or the trigonometric
// interpolant of equally spaced samples, M_w = (1/K) Σ_k M(t_k) e^{−j w Ωp t_k},
// |w| < K/2, plus half of the Nyquist term ±K/2 on each side for even K (so the real
// interpolant passes through every sample).
PeriodicSystem BuildSampled(const SceneModel& model, const internal::Constants& constants,
                            double period) {
  const int samples = static_cast<int>(model.sample_points.size());
  std::vector<double> times;
  for (const ExpressionEntry& entry : model.sample_points) {
    const double value = Value(entry, constants);
    const double t = model.points_are_azimuths ? value / 360 * period : value;
    const double limit = model.points_are_azimuths ? 360 : period;
    if (value < 0 || value >= limit)
      throw SceneError(entry.where + ": " + internal::FormatValue(value) + " is outside [0, " +
                       internal::FormatValue(limit) + ")" +
                       (model.points_are_azimuths ? " degrees" : " = [0, T)"));
    if (!times.empty() && t <= times.back())
      throw SceneError(entry.where + ": sample points must be strictly increasing");
    times.push_back(t);
  }
  if (model.fourier_interpolation) {
    for (int k = 0; k < samples; ++k)
      if (std::abs(times[k] - times[0] - period * k / samples) > 1e-9 * period)
        throw SceneError(model.sample_points[k].where +
                         ": fourier interpolation needs equally spaced samples over one "
                         "period (spacing T/K)");
  }
  // Sample k of matrix `key` (K matrices or one constant), evaluated; empty if absent.
  auto value = [&](const std::string& key, int k) -> Eigen::MatrixXd {
    const auto it = model.sample_matrices.find(key);
    if (it == model.sample_matrices.end() || it->second.empty()) return {};
    const ExpressionMatrixText& text = it->second.size() == 1 ? it->second[0] : it->second[k];
    Eigen::MatrixXd m(Rows(text), Cols(text));
    for (int r = 0; r < m.rows(); ++r)
      for (int c = 0; c < m.cols(); ++c) m(r, c) = Value(text[r][c], constants);
    return m;
  };
  std::vector<LtiSystem> systems(samples);
  for (int k = 0; k < samples; ++k)
    systems[k] = {value("A", k), value("B", k), value("C", k), value("D", k)};
  if (!model.fourier_interpolation) return PeriodicSystem::FromSamples(period, times, systems);

  const double omega_p = 2 * std::numbers::pi / period;
  auto series = [&](auto member, int rows, int cols) {
    if (rows == 0 || cols == 0 || (systems[0].*member).size() == 0) return FourierMatrix();
    const int top = samples / 2;
    FourierMatrix f(rows, cols, top);
    for (int w = 0; w <= top; ++w) {
      Eigen::MatrixXcd c = Eigen::MatrixXcd::Zero(rows, cols);
      for (int k = 0; k < samples; ++k)
        c += (systems[k].*member).template cast<std::complex<double>>() *
             std::polar(1.0 / samples, -w * omega_p * times[k]);
      if (2 * w == samples) c /= 2;  // Nyquist: split between +K/2 and −K/2
      if (w == 0) c = c.real().cast<std::complex<double>>();
      f.SetHarmonic(w, c);
    }
    return f;
  };
  const int n = model.states, m = model.inputs, p = model.outputs;
  return PeriodicSystem::FromFourier(period, series(&LtiSystem::A, n, n),
                                     series(&LtiSystem::B, n, m), series(&LtiSystem::C, p, n),
                                     series(&LtiSystem::D, p, m));
}

void CheckCoefficients(const PeriodicSystem& system, const std::string& where);

// A second_order block with matrices from files: the exact Fourier series of every matrix
// (expression matrices beside them must be constant in t), one Fourier-form system.
PeriodicSystem BuildSecondOrderSeries(const SceneModel& model, const internal::Constants& constants,
                                      double period) {
  if (!model.breakpoints.empty())
    throw SceneError(model.breakpoints[0].where +
                     ": matrices from files are Fourier series, which do not jump");
  internal::ExpressionMatrices compiler(constants, period);
  auto series = [&](const std::string& name) -> FourierMatrix {
    if (const auto f = model.file_matrices.find(name); f != model.file_matrices.end())
      return internal::FileMatrixSeries(
          f->second, [&](const ExpressionEntry& e) { return Value(e, constants); });
    const auto e = model.matrices.find(name);
    if (e == model.matrices.end() || e->second.empty()) return {};
    const std::optional<Eigen::MatrixXd> value = compiler.ConstantValue(compiler.Add(e->second));
    if (!value)
      throw SceneError(e->second[0][0].where.substr(0, e->second[0][0].where.find(": ")) + ": " +
                       name +
                       " depends on t beside matrices from files: give its periodic part as "
                       "file harmonics too");
    return FourierMatrix::Constant(*value);
  };
  std::optional<PeriodicSystem> system;
  try {
    system = FromSecondOrderSeries(period, series("M"), series("D"), series("K"), series("F"),
                                   series("Cd"), series("Cv"));
  } catch (const SingularMassError& e) {
    throw SingularMassError(model.mass_where + ": " + e.what());
  }
  CheckCoefficients(*system, model.mass_where);
  system = system->WithLabels(model.labels);
  if (model.rotor_speed) system = system->WithRotorSpeed(Value(*model.rotor_speed, constants));
  return *system;
}

PeriodicSystem BuildFromModel(const SceneModel& model, const ParameterMap& parameters) {
  const internal::Constants constants(parameters.begin(), parameters.end());
  const ExpressionEntry& period_entry = model.period ? *model.period : *model.omega;
  const double value = Value(period_entry, constants);
  const double period = model.period ? value : 2 * std::numbers::pi / value;
  if (!(value > 0) || !std::isfinite(period))
    throw SceneError(period_entry.where + ": must be > 0, got '" + period_entry.text +
                     "' = " + internal::FormatValue(value));

  std::vector<double> explicit_breakpoints;
  for (const ExpressionEntry& b : model.breakpoints) {
    const double t = Value(b, constants);
    if (t < 0 || t >= period)
      throw SceneError(b.where + ": breakpoint " + internal::FormatValue(t) +
                       " is outside [0, T) = [0, " + internal::FormatValue(period) + ")");
    explicit_breakpoints.push_back(t);
  }

  if (model.sampled) {
    if (!model.breakpoints.empty())
      throw SceneError(model.breakpoints[0].where +
                       ": a sampled scene has its breakpoints at the sample times");
    PeriodicSystem system = BuildSampled(model, constants, period).WithLabels(model.labels);
    if (model.rotor_speed) system = system.WithRotorSpeed(Value(*model.rotor_speed, constants));
    return system;
  }

  if (!model.file_matrices.empty()) return BuildSecondOrderSeries(model, constants, period);
  internal::ExpressionMatrices compiler(constants, period);
  std::map<std::string, int> handles;
  for (const auto& [name, text] : model.matrices)
    if (!text.empty()) handles[name] = compiler.Add(text);
  const std::vector<double> breakpoints =
      MergeBreakpoints(std::move(explicit_breakpoints), compiler.jumps(), period);
  const auto functions = compiler.Finish();
  auto function = [&](const std::string& name) -> PeriodicSystem::MatrixFunction {
    const auto it = handles.find(name);
    return it == handles.end() ? nullptr : functions[it->second];
  };

  std::optional<PeriodicSystem> system;
  if (model.second_order) {
    SecondOrderSystem s;
    s.period = period;
    s.dofs = model.states / 2;
    s.inputs = model.inputs;
    s.outputs = model.outputs;
    s.M = function("M");
    s.D = function("D");
    s.K = function("K");
    s.F = function("F");
    s.Cd = function("Cd");
    s.Cv = function("Cv");
    s.breakpoints = breakpoints;
    try {
      system = FromSecondOrder(s);
    } catch (const SingularMassError& e) {
      throw SingularMassError(model.mass_where + ": " + e.what());
    }
    CheckCoefficients(*system, model.mass_where);
  } else {
    PeriodicSystem::Functions f{function("A"), function("B"), function("C"), function("D")};
    system = PeriodicSystem::FromFunctions(period, model.states, model.inputs, model.outputs,
                                           std::move(f), breakpoints);
    const auto a = model.matrices.find("A");
    CheckCoefficients(*system,
                      a != model.matrices.end() && !a->second.empty() && !a->second[0].empty()
                          ? a->second[0][0].where.substr(0, a->second[0][0].where.find(':'))
                          : std::string("scene"));
  }
  system = system->WithLabels(model.labels);
  if (model.rotor_speed) system = system->WithRotorSpeed(Value(*model.rotor_speed, constants));
  return *system;
}

void CheckCoefficients(const PeriodicSystem& system, const std::string& where) {
  if (const auto problem = UnboundedCoefficients(system)) throw SceneError(where + ": " + *problem);
  if (const auto problem = NonPeriodicCoefficients(system))
    throw SceneError(where + ": " + *problem);
}

YAML::Node LoadYaml(const std::string& text, const std::string& source) {
  if (const auto problem = NotUtf8(text, "scene files are UTF-8"))
    throw SceneError(source + ": " + *problem);
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    std::string where = source;
    if (e.mark.line >= 0) where += ":" + std::to_string(e.mark.line + 1);
    throw SceneError(where + ": YAML syntax error: " + e.msg);
  }
}

}  // namespace

Scene ParseSceneYaml(const std::string& text, const std::string& source) {
  const Reader reader(source);
  const YAML::Node root = LoadYaml(text, source);
  if (!root.IsMap())
    throw SceneError(reader.Where(root, "") +
                     ": a scene file must be a mapping with period (or omega) and a "
                     "state_space, second_order or sampled block");
  reader.CheckKeys(root, "",
                   {"name", "description", "period", "omega", "parameters",
                    "parameter_descriptions", "breakpoints", "rotor_speed", "inputs", "outputs",
                    "states", "whirl_pairs", "state_space", "second_order", "sampled"});

  Scene scene;
  scene.source = source;
  scene.name = root["name"] ? reader.Scalar(root["name"], "name")
                            : std::filesystem::path(source).stem().string();
  if (root["description"]) scene.description = reader.Scalar(root["description"], "description");

  if (const YAML::Node parameters = root["parameters"]) {
    if (!parameters.IsMap())
      reader.Fail(parameters, "parameters", "expected a mapping name: default, e.g. {k: 10}");
    for (const auto& item : parameters) {
      const std::string name = item.first.Scalar();
      const std::string entry = "parameters." + name;
      if (!internal::IsIdentifier(name))
        reader.Fail(item.first, entry, "'" + name + "' is not a valid parameter name");
      if (internal::IsReservedName(name))
        reader.Fail(item.first, entry,
                    "parameter '" + name + "' would shadow the built-in '" + name +
                        "' (t is time, pi and functions are predefined)");
      const double value = Value(reader.Expression(item.second, entry), {});
      scene.parameters.push_back({name, value, ""});
    }
  }
  if (const YAML::Node descriptions = root["parameter_descriptions"]) {
    if (!descriptions.IsMap())
      reader.Fail(descriptions, "parameter_descriptions", "expected a mapping name: text");
    for (const auto& item : descriptions) {
      const std::string name = item.first.Scalar();
      auto it = std::find_if(scene.parameters.begin(), scene.parameters.end(),
                             [&](const SceneParameter& p) { return p.name == name; });
      if (it == scene.parameters.end())
        reader.Fail(item.first, "parameter_descriptions." + name, "no such parameter");
      it->description = reader.Scalar(item.second, "parameter_descriptions." + name);
    }
  }

  SceneModel model;
  if (root["period"] && root["omega"])
    reader.Fail(Reader::KeyMark(root, "omega"), "omega", "give either period or omega, not both");
  if (root["period"]) {
    model.period = reader.Expression(root["period"], "period");
  } else if (root["omega"]) {
    model.omega = reader.Expression(root["omega"], "omega");
  } else {
    reader.Fail(root, "", "missing 'period' (or 'omega', with T = 2*pi/omega)");
  }
  if (const YAML::Node breakpoints = root["breakpoints"]) {
    if (!breakpoints.IsSequence())
      reader.Fail(breakpoints, "breakpoints", "expected a list of times, e.g. [pi/2, 3*pi/2]");
    for (size_t i = 0; i < breakpoints.size(); ++i)
      model.breakpoints.push_back(
          reader.Expression(breakpoints[i], "breakpoints[" + std::to_string(i) + "]"));
  }
  if (root["rotor_speed"])
    model.rotor_speed = reader.Expression(root["rotor_speed"], "rotor_speed");

  if (root["state_space"] && root["second_order"])
    reader.Fail(Reader::KeyMark(root, "second_order"), "second_order",
                "give either state_space or second_order, not both");
  if (root["sampled"] && (root["state_space"] || root["second_order"]))
    reader.Fail(Reader::KeyMark(root, "sampled"), "sampled",
                "give one of state_space, second_order or sampled");
  if (root["sampled"]) {
    ReadSampled(reader, root, model);
  } else if (root["state_space"]) {
    ReadStateSpace(reader, root, model);
  } else if (root["second_order"]) {
    model.second_order = true;
    ReadSecondOrder(reader, root, model);
  } else {
    reader.Fail(root, "",
                "missing 'state_space' (A, B, C, D), 'second_order' (M, D, K, F) or 'sampled' "
                "(matrices at sample times)");
  }
  CheckLabels(reader, root, "states", model.labels.states, model.states);
  CheckLabels(reader, root, "inputs", model.labels.inputs, model.inputs);
  CheckLabels(reader, root, "outputs", model.labels.outputs, model.outputs);
  ReadWhirlPairs(reader, root, model.labels);

  scene.build = [model = std::move(model)](const ParameterMap& parameters) {
    return BuildFromModel(model, parameters);
  };
  // Build once with the defaults so that unknown names, bad expressions and NaNs are reported
  // when the file is loaded, not in the middle of a command.
  scene.Build();
  return scene;
}

Scene LoadSceneFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw SceneError(path + ": cannot open scene file");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw SceneError(path + ": cannot read scene file");
  return ParseSceneYaml(text.str(), path);
}

}  // namespace ltp
