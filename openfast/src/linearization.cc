// OpenFAST `.lin` files: reader, writer, operating-point sets and the sampled system
// (format and conventions in ltp/openfast/linearization.h).
#include "ltp/openfast/linearization.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/core/text.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

std::string Shorten(const std::string& s) { return s.size() <= 40 ? s : s.substr(0, 37) + "..."; }

struct Token {
  std::string text;
  size_t begin = 0, end = 0;  // offsets in the line
};

std::vector<Token> Tokenize(const std::string& line) {
  std::vector<Token> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i == line.size()) break;
    const size_t begin = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    tokens.push_back({line.substr(begin, i - begin), begin, i});
  }
  return tokens;
}

// A number as Fortran writes it: 1.0E+00, 1.0D+00, and 1.0+100 / 1.0-100 (three-digit
// exponents lose their letter). False when the token is not a number.
bool ParseNumber(const std::string& token, double* value) {
  if (token.empty()) return false;
  std::string s = token;
  for (char& c : s)
    if (c == 'D' || c == 'd') c = 'E';
  const char* begin = s.c_str();
  char* end = nullptr;
  double v = std::strtod(begin, &end);
  if (end != begin && *end != '\0') {
    // Mantissa followed by a signed exponent without its letter.
    const size_t at = static_cast<size_t>(end - begin);
    if ((s[at] == '+' || s[at] == '-') && at > 0 &&
        (std::isdigit(static_cast<unsigned char>(s[at - 1])) || s[at - 1] == '.') &&
        s.find_first_not_of("0123456789", at + 1) == std::string::npos && at + 1 < s.size()) {
      s.insert(at, "E");
      begin = s.c_str();
      v = std::strtod(begin, &end);
    }
  }
  if (end == begin || *end != '\0') return false;
  *value = v;
  return true;
}

class Parser {
 public:
  Parser(const std::string& text, std::string source) : source_(std::move(source)) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(line);
    }
  }

  LinFile Parse() {
    LinFile f;
    f.path = source_;
    const size_t body = ReadHeader(f);
    ReadBody(body, f);
    return f;
  }

 private:
  // Header: "Key: value [unit]" lines up to the first table or matrix. Returns the first line
  // of the body.
  size_t ReadHeader(LinFile& f) const {
    size_t i = 0;
    bool have_states_count = false;
    for (; i < lines_.size(); ++i) {
      const std::string line = Trim(lines_[i]);
      if (line.empty()) continue;
      if (f.title.empty()) f.title = line;
      if (StartsWith(line, "Order of") || MatrixHeader(line)) break;
      const auto colon = line.find(':');
      if (colon == std::string::npos) continue;
      if (ReadHeaderField(i, Trim(line.substr(0, colon)), Trim(line.substr(colon + 1)), f))
        have_states_count = true;
    }
    if (!have_states_count)
      Fail(0,
           "expected 'Number of continuous states:' in the header (is this an OpenFAST .lin "
           "file?)");
    return i;
  }

  // One header field; true when it was the number of continuous states.
  bool ReadHeaderField(size_t i, const std::string& field, const std::string& value,
                       LinFile& f) const {
    const std::string key = Lower(field);
    auto number = [&]() {
      double v = 0;
      const auto tokens = Tokenize(value);
      if (tokens.empty() || !ParseNumber(tokens[0].text, &v) || !std::isfinite(v))
        Fail(i, "expected a number after '" + field + ":', got '" + Shorten(value) + "'");
      return v;
    };
    auto count = [&]() {
      const double v = number();
      if (v < 0 || v != std::floor(v) || v > 1e7)
        Fail(i, "expected a non-negative whole number after '" + field + ":', got '" +
                    Shorten(value) + "'");
      return static_cast<int>(v);
    };
    if (key == "simulation time")
      f.simulation_time = number();
    else if (key == "rotor speed")
      f.rotor_speed = number();
    else if (key == "azimuth")
      f.azimuth = number();
    else if (key == "wind speed")
      f.wind_speed = number();
    else if (key == "number of continuous states") {
      f.continuous_states = count();
      return true;
    } else if (key == "number of discrete states")
      f.discrete_states = count();
    else if (key == "number of constraint states")
      f.constraint_states = count();
    else if (key == "number of inputs")
      f.inputs = count();
    else if (key == "number of outputs")
      f.outputs = count();
    else if (key == "jacobians included in this file?") {
      const std::string v = Lower(value);
      if (StartsWith(v, "yes") || v == "t" || v == "true")
        f.jacobians_included = true;
      else if (StartsWith(v, "no") || v == "f" || v == "false")
        f.jacobians_included = false;
      else
        Fail(i, "expected Yes or No after 'Jacobians included in this file?', got '" +
                    Shorten(value) + "'");
    }
    return false;
  }

  // The tables ("Order of ...") and matrices, from line i to the end.
  void ReadBody(size_t i, LinFile& f) const {
    bool have_states = false;
    std::map<std::string, size_t> seen_matrices;
    for (; i < lines_.size(); ++i) {
      const std::string line = Trim(lines_[i]);
      if (line.empty()) continue;
      if (StartsWith(line, "Order of")) {
        if (IsStateTable(line)) have_states = true;
        i = ReadChannelTable(i, line, f);
        continue;
      }
      std::string name;
      int rows = 0, cols = 0;
      if (MatrixHeader(line, &name, &rows, &cols)) {
        if (seen_matrices.count(name))
          Fail(i, "matrix " + name + " appears twice (first at line " +
                      std::to_string(seen_matrices[name] + 1) + ")");
        seen_matrices[name] = i;
        MatrixXd m;
        const size_t header = i;
        i = ReadMatrix(i, name, rows, cols, &m);
        StoreMatrix(header, name, std::move(m), f);
        continue;
      }
      // Anything else ("Linearized state matrices:", "Jacobian matrices:") is a caption.
    }
    if (f.continuous_states > 0 && !have_states)
      Fail(lines_.empty() ? 0 : lines_.size() - 1,
           "expected the table 'Order of continuous states:' (" +
               std::to_string(f.continuous_states) + " rows) before the end of the file");
  }

  static bool IsStateTable(const std::string& caption) {
    const std::string what = Lower(caption);
    return what.find("continuous state derivatives") == std::string::npos &&
           what.find("continuous states") != std::string::npos;
  }

  // The table captioned at line i into its field of f (discrete and constraint states are read
  // and dropped); returns the table's last line.
  size_t ReadChannelTable(size_t i, const std::string& caption, LinFile& f) const {
    const std::string what = Lower(caption);
    std::vector<LinChannel>* target = nullptr;
    int rows = -1;  // -1: unknown table, read to the next blank line
    int default_order = 0;
    if (what.find("continuous state derivatives") != std::string::npos) {
      target = &f.state_derivatives;
      rows = f.continuous_states;
      default_order = 2;
    } else if (what.find("continuous states") != std::string::npos) {
      target = &f.states;
      rows = f.continuous_states;
      default_order = 2;
    } else if (what.find("discrete states") != std::string::npos) {
      rows = f.discrete_states;
    } else if (what.find("constraint states") != std::string::npos) {
      rows = f.constraint_states;
    } else if (what.find("inputs") != std::string::npos) {
      target = &f.input_channels;
      rows = f.inputs;
    } else if (what.find("outputs") != std::string::npos) {
      target = &f.output_channels;
      rows = f.outputs;
    }
    std::vector<LinChannel> table;
    i = ReadTable(i, rows, default_order, &table);
    if (target) *target = std::move(table);
    return i;
  }

  [[noreturn]] void Fail(size_t line, const std::string& message) const {
    throw SceneError(source_ + ":" + std::to_string(line + 1) + ": " + message);
  }

  // "A: 20 x 20" (any identifier: A, B, C, D, dUdu, dUdy, ...).
  static bool MatrixHeader(const std::string& line, std::string* name = nullptr,
                           int* rows = nullptr, int* cols = nullptr) {
    const auto colon = line.find(':');
    if (colon == std::string::npos || colon == 0) return false;
    const std::string id = Trim(line.substr(0, colon));
    if (id.empty() || !(std::isalpha(static_cast<unsigned char>(id[0])) || id[0] == '_'))
      return false;
    for (char c : id)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
    const std::string rest = Trim(line.substr(colon + 1));
    const auto x = rest.find_first_of("xX");
    if (x == std::string::npos) return false;
    const std::string a = Trim(rest.substr(0, x)), b = Trim(rest.substr(x + 1));
    if (a.empty() || b.empty() || a.find_first_not_of("0123456789") != std::string::npos ||
        b.find_first_not_of("0123456789") != std::string::npos || a.size() > 8 || b.size() > 8)
      return false;
    if (name) *name = id;
    if (rows) *rows = std::stoi(a);
    if (cols) *cols = std::stoi(b);
    return true;
  }

  // Reads the table starting at the "Order of ...:" line `at`; returns the index of its last
  // line.
  size_t ReadTable(size_t at, int rows, int default_order, std::vector<LinChannel>* out) const {
    const std::string title = Trim(lines_[at]);
    size_t i = at + 1;
    while (i < lines_.size() && Trim(lines_[i]).empty()) ++i;
    if (i >= lines_.size() || Trim(lines_[i]).find("Row/Column") == std::string::npos)
      Fail(std::min(i, lines_.size() - 1),
           "expected the column header 'Row/Column Operating Point ...' of table '" + title + "'");
    const std::string header = lines_[i];
    const bool has_rotating = header.find("Rotating Frame") != std::string::npos;
    const bool has_order = header.find("Derivative Order") != std::string::npos;
    ++i;
    if (i < lines_.size() && StartsWith(Trim(lines_[i]), "---")) ++i;
    int r = 0;
    for (; rows < 0 || r < rows; ++r, ++i) {
      if (i >= lines_.size() || Trim(lines_[i]).empty()) {
        if (rows < 0) break;
        Fail(std::min(i, lines_.size() - 1),
             "expected row " + std::to_string(r + 1) + " of " + std::to_string(rows) +
                 " in table '" + title + "', found " +
                 (i >= lines_.size() ? std::string("the end of the file") : "a blank line"));
      }
      const std::string& line = lines_[i];
      const std::vector<Token> t = Tokenize(line);
      size_t k = 0;
      double value = 0;
      if (t.empty() || !ParseNumber(t[k].text, &value) || value != r + 1)
        Fail(i, "expected row number " + std::to_string(r + 1) + " of table '" + title +
                    "', got '" + Shorten(t.empty() ? line : t[k].text) + "'");
      ++k;
      LinChannel c;
      c.derivative_order = default_order;
      // Operating point: one value, or several separated by commas (orientations).
      while (true) {
        if (k >= t.size())
          Fail(i, "expected the operating point in row " + std::to_string(r + 1) + " of '" + title +
                      "'");
        std::string text = t[k].text;
        const bool more = !text.empty() && text.back() == ',';
        if (more) text.pop_back();
        if (text.find("****") != std::string::npos)
          Fail(i, "operating point '" + t[k].text +
                      "' overflowed its Fortran field (****): rerun OpenFAST with a wider "
                      "output format");
        if (!ParseNumber(text, &value))
          Fail(i, "expected a number for the operating point in row " + std::to_string(r + 1) +
                      " of '" + title + "', got '" + Shorten(t[k].text) + "'");
        c.operating_point_values.push_back(value);
        ++k;
        if (!more) break;
      }
      c.operating_point = c.operating_point_values.front();
      if (has_rotating) {
        const std::string flag = k < t.size() ? t[k].text : "";
        if (flag == "T" || flag == "True" || flag == "t")
          c.rotating_frame = true;
        else if (flag == "F" || flag == "False" || flag == "f")
          c.rotating_frame = false;
        else
          Fail(i, "expected T or F in the 'Rotating Frame?' column of row " +
                      std::to_string(r + 1) + ", got '" + Shorten(flag) + "'");
        ++k;
      }
      if (has_order) {
        if (k >= t.size() || !ParseNumber(t[k].text, &value) || value < 0 || value > 2 ||
            value != std::floor(value))
          Fail(i, "expected the derivative order (0, 1 or 2) in row " + std::to_string(r + 1) +
                      " of '" + title + "', got '" + (k < t.size() ? Shorten(t[k].text) : "") +
                      "'");
        c.derivative_order = static_cast<int>(value);
        ++k;
      }
      if (k >= t.size())
        Fail(i, "expected a description in row " + std::to_string(r + 1) + " of '" + title + "'");
      c.description = Trim(line.substr(t[k].begin));
      out->push_back(std::move(c));
    }
    return i - 1;
  }

  size_t ReadMatrix(size_t at, const std::string& name, int rows, int cols, MatrixXd* m) const {
    // Sizes the file cannot hold are refused before anything is allocated (a header can claim
    // 99 999 999² entries).
    if (rows < 0 || cols < 0 || static_cast<size_t>(rows) > lines_.size() - at - 1)
      Fail(at, "matrix " + name + " declares " + std::to_string(rows) +
                   " rows but the file has only " + std::to_string(lines_.size() - at - 1) +
                   " lines after its header");
    // A row of `cols` numbers takes at least 2·cols − 1 characters.
    size_t longest = 0;
    for (size_t i = at + 1; i <= at + static_cast<size_t>(rows); ++i)
      longest = std::max(longest, lines_[i].size());
    if (static_cast<size_t>(cols) > (longest + 1) / 2)
      Fail(at, "matrix " + name + " declares " + std::to_string(cols) +
                   " columns but its longest row has " + std::to_string(longest) +
                   " characters, too few for that many numbers");
    m->resize(rows, cols);
    size_t i = at + 1;
    for (int r = 0; r < rows; ++r, ++i) {
      if (i >= lines_.size())
        Fail(lines_.size() - 1, "expected row " + std::to_string(r + 1) + " of " +
                                    std::to_string(rows) + " of matrix " + name +
                                    ", found the end of the file");
      const std::vector<Token> t = Tokenize(lines_[i]);
      if (static_cast<int>(t.size()) != cols)
        Fail(i, "expected " + std::to_string(cols) + " numbers in row " + std::to_string(r + 1) +
                    " of matrix " + name + " (" + std::to_string(rows) + " x " +
                    std::to_string(cols) + "), found " + std::to_string(t.size()));
      for (int c = 0; c < cols; ++c) {
        double v = 0;
        if (t[c].text.find("****") != std::string::npos)
          Fail(i, "entry (" + std::to_string(r + 1) + ", " + std::to_string(c + 1) + ") of " +
                      name + " overflowed its Fortran field (" + t[c].text + ")");
        if (!ParseNumber(t[c].text, &v))
          Fail(i, "expected a number at entry (" + std::to_string(r + 1) + ", " +
                      std::to_string(c + 1) + ") of matrix " + name + ", got '" +
                      Shorten(t[c].text) + "'");
        if (!std::isfinite(v))
          Fail(i, "entry (" + std::to_string(r + 1) + ", " + std::to_string(c + 1) + ") of " +
                      name + " is " + t[c].text + ", not a finite number");
        (*m)(r, c) = v;
      }
    }
    // One row more than declared would otherwise pass as a caption and shift every later matrix.
    if (i < lines_.size()) {
      const std::vector<Token> extra = Tokenize(lines_[i]);
      double v = 0;
      if (static_cast<int>(extra.size()) == cols && cols > 0 && ParseNumber(extra[0].text, &v))
        Fail(i, "matrix " + name + " has more rows than its header declares (" +
                    std::to_string(rows) + " x " + std::to_string(cols) + ")");
    }
    return i - 1;
  }

  void StoreMatrix(size_t line, const std::string& name, MatrixXd m, LinFile& f) const {
    auto check = [&](int rows, int cols, const std::string& what) {
      if (m.rows() != rows || m.cols() != cols)
        Fail(line, "matrix " + name + " is " + std::to_string(m.rows()) + " x " +
                       std::to_string(m.cols()) + " but the header gives " + what + " (" +
                       std::to_string(rows) + " x " + std::to_string(cols) + ")");
    };
    const int n = f.continuous_states, in = f.inputs, out = f.outputs;
    if (name == "A") {
      check(n, n, "continuous states x continuous states");
      f.A = std::move(m);
    } else if (name == "B") {
      check(n, in, "continuous states x inputs");
      f.B = std::move(m);
    } else if (name == "C") {
      check(out, n, "outputs x continuous states");
      f.C = std::move(m);
    } else if (name == "D") {
      check(out, in, "outputs x inputs");
      f.D = std::move(m);
    }
    // Other matrices (dUdu, dUdy, ... when Jacobians are included) are read and checked for
    // numbers only.
  }

  std::string source_;
  std::vector<std::string> lines_;
};

bool HasLinExtension(const std::string& path) {
  const std::string ext = Lower(std::filesystem::path(path).extension().string());
  return ext == ".lin";
}

double WrapAzimuth(double psi) {
  double w = std::fmod(psi, 2 * pi);
  if (w < 0) w += 2 * pi;
  if (w >= 2 * pi) w = 0;
  return w;
}

// Index of each of `ref`'s channels in `other`, by description (the i-th repeat of a
// description matches the i-th repeat). Empty optional when one is missing: `missing` names it.
std::optional<std::vector<int>> MatchChannels(const std::vector<LinChannel>& ref,
                                              const std::vector<LinChannel>& other,
                                              std::string* missing) {
  std::map<std::string, std::vector<int>> where;
  for (size_t i = 0; i < other.size(); ++i)
    where[other[i].description].push_back(static_cast<int>(i));
  std::map<std::string, size_t> used;
  std::vector<int> index;
  for (const LinChannel& c : ref) {
    auto it = where.find(c.description);
    size_t& u = used[c.description];
    if (it == where.end() || u >= it->second.size()) {
      *missing = c.description;
      return std::nullopt;
    }
    index.push_back(it->second[u++]);
  }
  return index;
}

// Trigonometric interpolation of K samples at azimuths ψ_k: coefficient matrices a_0, a_h,
// b_h of  M(ψ) = a_0 + Σ_h a_h cos hψ + b_h sin hψ  as a Fourier series in Ωp t = ψ.
FourierMatrix TrigInterpolant(const std::vector<double>& psi, const std::vector<MatrixXd>& m) {
  const int K = static_cast<int>(psi.size());
  const int rows = static_cast<int>(m[0].rows()), cols = static_cast<int>(m[0].cols());
  if (rows == 0 || cols == 0) return FourierMatrix();
  const int H = K / 2;  // odd K: (K−1)/2; even K: K/2 (min-norm split of the Nyquist pair)
  const int unknowns = 1 + 2 * H;
  MatrixXd V(K, unknowns);
  for (int k = 0; k < K; ++k) {
    V(k, 0) = 1;
    for (int h = 1; h <= H; ++h) {
      V(k, 2 * h - 1) = std::cos(h * psi[k]);
      V(k, 2 * h) = std::sin(h * psi[k]);
    }
  }
  MatrixXd rhs(K, rows * cols);
  for (int k = 0; k < K; ++k)
    rhs.row(k) = Eigen::Map<const Eigen::RowVectorXd>(m[k].data(), rows * cols);
  // Minimum-norm solution (unique interpolant for odd K; V has full row rank for distinct ψ).
  const MatrixXd coeff = V.completeOrthogonalDecomposition().solve(rhs);
  auto entry = [&](int j) {
    return Eigen::Map<const MatrixXd>(coeff.row(j).eval().data(), rows, cols).eval();
  };
  FourierMatrix f(rows, cols, H);
  f.SetHarmonic(0, entry(0).cast<std::complex<double>>());
  for (int h = 1; h <= H; ++h) {
    const Eigen::MatrixXcd c =
        0.5 * (entry(2 * h - 1).cast<std::complex<double>>() -
               std::complex<double>(0, 1) * entry(2 * h).cast<std::complex<double>>());
    f.SetHarmonic(h, c);
  }
  return f;
}

std::string FormatNumber(double v, const char* format = "%.4f") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string Degrees(double rad) { return FormatNumber(rad * 180 / pi, "%.1f"); }

}  // namespace

LinFile ParseLinFile(const std::string& text, const std::string& source) {
  // State names end up in JSON and on terminals (OpenFAST writes ASCII).
  if (const auto problem = NotUtf8(text, "a .lin file is text (ASCII or UTF-8)"))
    throw SceneError(source + ": " + *problem);
  return Parser(text, source).Parse();
}

LinFile ReadLinFile(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw SceneError(path + ": is a directory, not a .lin file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the file");
  return ParseLinFile(text.str(), path);
}

std::string FormatLinFile(const LinFile& f) {
  if (!f.rotor_speed || !f.azimuth)
    throw InputError("FormatLinFile: rotor_speed and azimuth must be set");
  const int n = f.continuous_states;
  if (static_cast<int>(f.states.size()) != n ||
      (f.A.size() && (f.A.rows() != n || f.A.cols() != n)))
    throw InputError("FormatLinFile: the state table and A must have continuous_states rows");
  if (static_cast<int>(f.input_channels.size()) != f.inputs ||
      static_cast<int>(f.output_channels.size()) != f.outputs)
    throw InputError("FormatLinFile: the input/output tables must match inputs/outputs");
  std::ostringstream s;
  char buf[256];
  s << "\n" << (f.title.empty() ? "Linearized model: written by ltp" : f.title) << "\n\n";
  s << "Simulation information:\n";
  auto line = [&](const char* key, const std::string& value) {
    std::snprintf(buf, sizeof buf, "   %-34s%s\n", key, value.c_str());
    s << buf;
  };
  line("Simulation time:", FormatNumber(f.simulation_time.value_or(0), "%14.6f") + " s");
  line("Rotor Speed:", FormatNumber(*f.rotor_speed, "%24.16E") + " rad/s");
  line("Azimuth:", FormatNumber(*f.azimuth, "%24.16E") + " rad");
  if (f.wind_speed) line("Wind Speed:", FormatNumber(*f.wind_speed, "%14.6f") + " m/s");
  line("Number of continuous states:", std::to_string(n));
  line("Number of discrete states:", std::to_string(f.discrete_states));
  line("Number of constraint states:", std::to_string(f.constraint_states));
  line("Number of inputs:", std::to_string(f.inputs));
  line("Number of outputs:", std::to_string(f.outputs));
  line("Jacobians included in this file?", f.jacobians_included ? "Yes" : "No");
  s << "\n";
  auto table = [&](const char* title, const std::vector<LinChannel>& rows) {
    if (rows.empty()) return;
    s << title << "\n"
      << "   Row/Column Operating Point          Rotating Frame? Derivative Order Description\n"
      << "   ---------- ---------------          --------------- ---------------- -----------\n";
    for (size_t r = 0; r < rows.size(); ++r) {
      std::snprintf(buf, sizeof buf, "   %10zu  %24.16E  %14s  %15d         ", r + 1,
                    rows[r].operating_point, rows[r].rotating_frame ? "T" : "F",
                    rows[r].derivative_order);
      s << buf << rows[r].description << "\n";
    }
    s << "\n";
  };
  table("Order of continuous states:", f.states);
  table("Order of continuous state derivatives:", f.state_derivatives);
  table("Order of inputs:", f.input_channels);
  table("Order of outputs:", f.output_channels);
  s << "\nLinearized state matrices:\n\n";
  auto matrix = [&](const char* name, const MatrixXd& m) {
    if (m.size() == 0) return;
    s << name << ": " << m.rows() << " x " << m.cols() << "\n";
    for (int r = 0; r < m.rows(); ++r) {
      for (int c = 0; c < m.cols(); ++c) {
        std::snprintf(buf, sizeof buf, " %24.16E", m(r, c));
        s << buf;
      }
      s << "\n";
    }
    s << "\n";
  };
  matrix("A", f.A);
  matrix("B", f.B);
  matrix("C", f.C);
  matrix("D", f.D);
  return s.str();
}

void WriteLinFile(const std::string& path, const LinFile& file) {
  const std::string text = FormatLinFile(file);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError("cannot write '" + path + "'");
  out << text;
  if (!out) throw InputError("cannot write '" + path + "'");
}

bool LooksLikeLinInput(const std::string& argument) {
  if (HasLinExtension(argument)) return true;
  if (argument.find_first_of("*?[") != std::string::npos) return true;
  std::error_code error;
  return std::filesystem::is_directory(argument, error);
}

std::vector<std::string> ExpandLinPaths(const std::vector<std::string>& arguments) {
  std::vector<std::string> files;
  std::error_code error;
  for (const std::string& arg : arguments) {
    if (std::filesystem::is_directory(arg, error)) {
      std::vector<std::string> found;
      for (const auto& entry : std::filesystem::directory_iterator(arg, error))
        if (entry.is_regular_file(error) && HasLinExtension(entry.path().string()))
          found.push_back(entry.path().string());
      if (found.empty()) throw InputError("no .lin files in directory '" + arg + "'");
      files.insert(files.end(), found.begin(), found.end());
    } else if (arg.find_first_of("*?[") != std::string::npos &&
               !std::filesystem::exists(arg, error)) {
      glob_t g{};
      const int status = glob(arg.c_str(), 0, nullptr, &g);
      std::vector<std::string> found;
      if (status == 0)
        for (size_t i = 0; i < g.gl_pathc; ++i)
          if (HasLinExtension(g.gl_pathv[i]) &&
              std::filesystem::is_regular_file(g.gl_pathv[i], error))
            found.push_back(g.gl_pathv[i]);
      globfree(&g);
      if (found.empty()) throw InputError("no .lin file matches '" + arg + "'");
      files.insert(files.end(), found.begin(), found.end());
    } else {
      if (!std::filesystem::exists(arg, error)) throw InputError("no such file: '" + arg + "'");
      if (!HasLinExtension(arg))
        throw InputError("'" + arg +
                         "' is not an OpenFAST .lin file (expected the .lin "
                         "extension; scenes are given one at a time)");
      files.push_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

double LinOperatingPoint::period() const { return 2 * pi / rotor_speed; }

double LinOperatingPoint::SpacingDeviation() const {
  const int K = size();
  double worst = 0;
  for (int k = 0; k < K; ++k) {
    const double next = k + 1 < K ? azimuths[k + 1] : azimuths[0] + 2 * pi;
    worst = std::max(worst, std::abs(next - azimuths[k] - 2 * pi / K));
  }
  return worst;
}

namespace {

// Every file must give the rotor speed, its azimuth and a state matrix.
void CheckHeaders(const std::vector<LinFile>& files) {
  if (files.empty()) throw InputError("no .lin files given");
  for (const LinFile& f : files) {
    if (!f.rotor_speed)
      throw InputError(f.path + ": no 'Rotor Speed:' in the header: cannot tell the period");
    if (!f.azimuth) throw InputError(f.path + ": no 'Azimuth:' in the header");
    if (f.continuous_states == 0 || f.A.size() == 0)
      throw InputError(f.path + ": holds no state matrix A (" +
                       std::to_string(f.continuous_states) +
                       " continuous states): nothing to analyse");
  }
}

// Headers of one operating point agree to 1e-3 relative (OpenFAST writes 6–7 digits).
bool SameRotorSpeed(double speed, double reference) {
  const double d = std::abs(speed - reference);
  return d <= 1e-3 * std::max(std::abs(reference), 1e-12) || d <= 1e-12;
}
bool SameWindSpeed(double speed, double reference) {
  return std::abs(speed - reference) <= 1e-3 * std::max(std::abs(reference), 1.0);
}

// One model at one operating point: sizes, rotor speed and wind speed as the reference file's.
void CheckSameOperatingPoint(const LinFile& f, const LinFile& ref) {
  if (f.continuous_states != ref.continuous_states || f.inputs != ref.inputs ||
      f.outputs != ref.outputs)
    throw InputError(f.path + ": " + std::to_string(f.continuous_states) + " states, " +
                     std::to_string(f.inputs) + " inputs, " + std::to_string(f.outputs) +
                     " outputs, but " + ref.path + " has " + std::to_string(ref.continuous_states) +
                     ", " + std::to_string(ref.inputs) + ", " + std::to_string(ref.outputs) +
                     ": not one model");
  const double speed = *f.rotor_speed, ref_speed = *ref.rotor_speed;
  if (!SameRotorSpeed(speed, ref_speed))
    throw InputError(f.path + ": rotor speed " + FormatNumber(speed, "%.6g") + " rad/s but " +
                     ref.path + " has " + FormatNumber(ref_speed, "%.6g") +
                     " rad/s: the files are not one operating point");
  if (f.wind_speed && ref.wind_speed && !SameWindSpeed(*f.wind_speed, *ref.wind_speed))
    throw InputError(f.path + ": wind speed " + FormatNumber(*f.wind_speed, "%.6g") + " m/s but " +
                     ref.path + " has " + FormatNumber(*ref.wind_speed, "%.6g") +
                     " m/s: the files are not one operating point");
}

// File f's matrices with its states, inputs and outputs in the reference file's order (B, C,
// D only where every file has them).
LtiSystem SampleInReferenceOrder(const LinFile& f, const LinFile& ref, bool with_b, bool with_c,
                                 bool with_d) {
  std::string missing;
  const auto s = MatchChannels(ref.states, f.states, &missing);
  if (!s)
    throw InputError(f.path + ": has no state '" + missing + "' (found in " + ref.path +
                     "): the files are not one model");
  auto io = [&](const std::vector<LinChannel>& a, const std::vector<LinChannel>& b, int count,
                const char* what) {
    if (a.empty() || b.empty()) {  // tables not written: keep the order
      std::vector<int> identity(count);
      for (int i = 0; i < count; ++i) identity[i] = i;
      return identity;
    }
    const auto m = MatchChannels(a, b, &missing);
    if (!m)
      throw InputError(f.path + ": has no " + what + " '" + missing + "' (found in " + ref.path +
                       "): the files are not one model");
    return *m;
  };
  const std::vector<int> u = io(ref.input_channels, f.input_channels, f.inputs, "input");
  const std::vector<int> y = io(ref.output_channels, f.output_channels, f.outputs, "output");
  const int n = f.continuous_states;
  LtiSystem sample;
  sample.A.resize(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sample.A(i, j) = f.A((*s)[i], (*s)[j]);
  if (with_b) {
    sample.B.resize(n, f.inputs);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < f.inputs; ++j) sample.B(i, j) = f.B((*s)[i], u[j]);
  }
  if (with_c) {
    sample.C.resize(f.outputs, n);
    for (int i = 0; i < f.outputs; ++i)
      for (int j = 0; j < n; ++j) sample.C(i, j) = f.C(y[i], (*s)[j]);
  }
  if (with_d) {
    sample.D.resize(f.outputs, f.inputs);
    for (int i = 0; i < f.outputs; ++i)
      for (int j = 0; j < f.inputs; ++j) sample.D(i, j) = f.D(y[i], u[j]);
  }
  return sample;
}

// Rotor speed and acceleration from the operating point, as OpenFAST's MBC3 does: the
// derivatives of the generator azimuth (plus the drivetrain twist) and of its rate; the
// header's speed and 0 without them.
std::pair<double, double> OperatingSpeed(const LinFile& f) {
  const int n = f.continuous_states;
  double omega = *f.rotor_speed, omega_dot = 0;
  if (static_cast<int>(f.state_derivatives.size()) != n) return {omega, omega_dot};
  const std::vector<int> rate = RateOf(f.states);
  auto find = [&](const char* dof) -> std::pair<int, int> {  // displacement, rate
    for (int i = 0; i < n; ++i)
      if (rate[i] < 0 && f.states[i].description.find(dof) != std::string::npos)
        for (int j = 0; j < n; ++j)
          if (rate[j] == i) return {i, j};
    return {-1, -1};
  };
  const auto [g, g_rate] = find("DOF_GeAz");
  const auto [d, d_rate] = find("DOF_DrTr");
  if (g >= 0) {
    omega = f.state_derivatives[g].operating_point;
    omega_dot = f.state_derivatives[g_rate].operating_point;
    if (d >= 0) {
      omega += f.state_derivatives[d].operating_point;
      omega_dot += f.state_derivatives[d_rate].operating_point;
    }
  }
  return {omega, omega_dot};
}

// The rigid rotation: the generator azimuth (ElastoDyn), or another fixed-frame angle DOF
// named after the azimuth.
std::optional<int> FindAzimuthState(const std::vector<LinChannel>& states) {
  const std::vector<int> rate = RateOf(states);
  for (int i = 0; i < static_cast<int>(states.size()); ++i) {
    const LinChannel& c = states[i];
    const std::string d = Lower(c.description);
    if (rate[i] < 0 && !c.rotating_frame &&
        (c.description.find("DOF_GeAz") != std::string::npos ||
         d.find("gearbox_rot") != std::string::npos || d.find("azimuth") != std::string::npos))
      return i;
  }
  return std::nullopt;
}

// A file whose operating point turns the azimuth at another rate than its header's rotor
// speed contradicts itself (an edited header, files of another run): said, not averaged away.
// The .lin tables print 4 significant digits, so 1 % is beyond their rounding.
void NoteOperatingSpeeds(LinOperatingPoint& op) {
  for (size_t k = 0; k < op.files.size(); ++k) {
    const double header = op.rotor_speeds[k], rate = op.operating_speeds[k];
    if (std::abs(rate - header) <= 0.01 * std::abs(header)) continue;
    op.diagnostics.push_back(
        {DiagnosticCode::kOperatingSpeedDiffers, Severity::kWarning,
         op.files[k] + ": its operating point turns the azimuth at " + FormatNumber(rate, "%.4g") +
             " rad/s, its header says 'Rotor Speed: " + FormatNumber(header, "%.4g") + " rad/s' (" +
             FormatNumber(100 * (rate - header) / header, "%+.2g") +
             " %); the period uses the header's: check the file"});
  }
}

// Notes on uneven azimuths and on rotor speeds that differ between the files.
void NoteSpacingAndSpeeds(LinOperatingPoint& op) {
  const int K = op.size();
  if (K > 1 && op.SpacingDeviation() > 1e-3) {
    double lo = 1e300, hi = 0;
    for (int k = 0; k < K; ++k) {
      const double d = (k + 1 < K ? op.azimuths[k + 1] : op.azimuths[0] + 2 * pi) - op.azimuths[k];
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    op.diagnostics.push_back({DiagnosticCode::kAzimuthsUneven, Severity::kWarning,
                              "the " + std::to_string(K) +
                                  " azimuths are unevenly spaced: " + Degrees(lo) + "° to " +
                                  Degrees(hi) + "° apart (even: " + Degrees(2 * pi / K) + "°)"});
  }
  double spread = 0;
  for (double w : op.rotor_speeds) spread = std::max(spread, std::abs(w - op.rotor_speed));
  if (spread > 1e-12 * std::abs(op.rotor_speed))  // not the rounding of their mean
    op.diagnostics.push_back({DiagnosticCode::kRotorSpeedsDiffer, Severity::kNote,
                              "rotor speeds differ by up to " + FormatNumber(spread, "%.3g") +
                                  " rad/s between files; the period "
                                  "uses their mean"});
}

}  // namespace

LinOperatingPoint MakeLinOperatingPoint(std::vector<LinFile> files) {
  CheckHeaders(files);
  std::stable_sort(files.begin(), files.end(), [](const LinFile& a, const LinFile& b) {
    return WrapAzimuth(*a.azimuth) < WrapAzimuth(*b.azimuth);
  });
  const LinFile& ref = files.front();
  LinOperatingPoint op;
  op.wind_speed = ref.wind_speed;
  for (const LinChannel& c : ref.input_channels)
    if (c.description.find("collective blade-pitch command") != std::string::npos)
      op.collective_pitch = c.operating_point;
  op.states = ref.states;
  op.inputs = ref.input_channels;
  op.outputs = ref.output_channels;
  // B, C, D only when every file holds them.
  auto in_all = [&](const char* name, MatrixXd LinFile::*member) {
    int count = 0;
    for (const LinFile& f : files) count += (f.*member).size() > 0;
    if (count > 0 && count < static_cast<int>(files.size()))
      op.diagnostics.push_back(
          {DiagnosticCode::kMatrixDropped, Severity::kWarning,
           std::string("matrix ") + name + " is missing in some files and was dropped from all"});
    return count == static_cast<int>(files.size());
  };
  const bool all_b = in_all("B", &LinFile::B), all_c = in_all("C", &LinFile::C),
             all_d = in_all("D", &LinFile::D);
  for (const LinFile& f : files) {
    CheckSameOperatingPoint(f, ref);
    op.samples.push_back(SampleInReferenceOrder(f, ref, all_b, all_c, all_d));
    op.files.push_back(f.path);
    op.azimuths.push_back(WrapAzimuth(*f.azimuth));
    op.rotor_speeds.push_back(*f.rotor_speed);
    const auto [omega, omega_dot] = OperatingSpeed(f);
    op.operating_speeds.push_back(omega);
    op.operating_accelerations.push_back(omega_dot);
  }
  for (size_t k = 1; k < op.azimuths.size(); ++k)
    if (op.azimuths[k] - op.azimuths[k - 1] < 1e-6)
      throw InputError(op.files[k] + " and " + op.files[k - 1] + " are both at azimuth " +
                       FormatNumber(op.azimuths[k], "%.6g") +
                       " rad: one file per azimuth (are they two operating points?)");
  double sum = 0;
  for (double w : op.rotor_speeds) sum += w;
  op.rotor_speed = sum / static_cast<double>(op.rotor_speeds.size());
  op.azimuth_state = FindAzimuthState(op.states);
  NoteSpacingAndSpeeds(op);
  NoteOperatingSpeeds(op);
  return op;
}

namespace {
std::string LinRootName(const std::filesystem::path& file);
}  // namespace

LinOperatingPoint ReadLinOperatingPoint(const std::vector<std::string>& arguments) {
  std::vector<LinFile> files;
  for (const std::string& path : ExpandLinPaths(arguments)) files.push_back(ReadLinFile(path));
  try {
    return MakeLinOperatingPoint(std::move(files));
  } catch (const InputError& e) {
    const auto groups = GroupLinFiles(arguments);
    if (groups.size() < 2) throw;
    std::string roots;
    for (size_t g = 0; g < groups.size() && g < 4; ++g) {
      const std::string root = LinRootName(groups[g].front());
      roots += (g ? ", " : "") + (root.empty() ? groups[g].front() : root + ".*.lin");
    }
    throw InputError(std::string(e.what()) + " — the files are " + std::to_string(groups.size()) +
                     " OpenFAST simulations (" + roots + (groups.size() > 4 ? ", …" : "") +
                     "): name the files of one (a quoted glob), or draw them all with ltp "
                     "campbell");
  }
}

namespace {

// `<root>.<k>.lin` → root; "" for a name without the linearisation number.
std::string LinRootName(const std::filesystem::path& file) {
  std::string name = file.filename().string();
  name = name.substr(0, name.size() - 4);  // ".lin" (ExpandLinPaths checked the extension)
  const size_t dot = name.find_last_of('.');
  if (dot == std::string::npos || dot + 1 == name.size()) return "";
  for (size_t i = dot + 1; i < name.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return "";
  return name.substr(0, dot);
}

// The files of one group split by the operating condition in their headers (rotor speed and
// wind speed as MakeLinOperatingPoint accepts them; a header without one is its own group).
std::vector<std::vector<LinFile>> SplitByOperatingCondition(std::vector<LinFile> files) {
  std::vector<std::vector<LinFile>> points;
  auto near = [](const std::optional<double>& a, const std::optional<double>& b,
                 bool (*same)(double, double)) {
    return a && b ? same(*a, *b) : a.has_value() == b.has_value();
  };
  for (LinFile& f : files) {
    auto same = std::find_if(points.begin(), points.end(), [&](const std::vector<LinFile>& p) {
      return near(f.rotor_speed, p.front().rotor_speed, SameRotorSpeed) &&
             near(f.wind_speed, p.front().wind_speed, SameWindSpeed);
    });
    if (same == points.end())
      points.push_back({std::move(f)});
    else
      same->push_back(std::move(f));
  }
  return points;
}

}  // namespace

std::vector<std::vector<std::string>> GroupLinFiles(const std::vector<std::string>& arguments) {
  std::vector<std::vector<std::string>> groups;
  std::map<std::pair<std::string, std::string>, size_t> index;  // (directory, root) → group
  for (const std::string& file : ExpandLinPaths(arguments)) {
    const std::filesystem::path path(file);
    const auto key = std::make_pair(path.parent_path().string(), LinRootName(path));
    const auto [at, added] = index.emplace(key, groups.size());
    if (added) groups.emplace_back();
    groups[at->second].push_back(file);
  }
  return groups;
}

std::vector<LinOperatingPoint> ReadLinOperatingPoints(const std::vector<std::string>& arguments,
                                                      std::vector<std::string>* failures) {
  std::vector<LinOperatingPoint> points;
  for (const std::vector<std::string>& group : GroupLinFiles(arguments)) {
    try {
      std::vector<LinFile> files;
      for (const std::string& path : group) files.push_back(ReadLinFile(path));
      for (std::vector<LinFile>& point : SplitByOperatingCondition(std::move(files))) {
        const std::string first = point.front().path;
        try {
          points.push_back(MakeLinOperatingPoint(std::move(point)));
        } catch (const InputError& e) {
          if (!failures) throw;
          failures->push_back(first + " and the files at its operating point: " + e.what());
        }
      }
    } catch (const Error& e) {
      if (!failures) throw;
      failures->push_back(group.front() + " (" + std::to_string(group.size()) +
                          " files): " + e.what());
    }
  }
  if (points.empty())
    throw InputError("no operating point could be read" +
                     (failures && !failures->empty() ? ": " + failures->front() : std::string()));
  return points;
}

double AzimuthLebesgueConstant(const std::vector<double>& azimuths) {
  const int K = static_cast<int>(azimuths.size());
  if (K <= 1) return 1;
  // ℓ_k for every k at once: the interpolant of the identity's columns (TrigInterpolant's
  // minimum-norm rule), evaluated on a grid fine enough for degree K/2.
  std::vector<MatrixXd> unit;
  for (int k = 0; k < K; ++k) {
    MatrixXd e = MatrixXd::Zero(K, 1);
    e(k) = 1;
    unit.push_back(e);
  }
  const FourierMatrix l = TrigInterpolant(azimuths, unit);
  const int grid = 64 * K;
  double worst = 0;
  for (int g = 0; g < grid; ++g)
    worst = std::max(worst, l.Evaluate(2 * pi * g / grid, 1.0).cwiseAbs().sum());
  return worst;
}

std::optional<std::string> AzimuthSamplingProblem(const std::vector<double>& azimuths) {
  const double lebesgue = AzimuthLebesgueConstant(azimuths);
  if (lebesgue <= kMaxAzimuthLebesgueConstant) return std::nullopt;
  std::string list;
  for (double a : azimuths) list += (list.empty() ? "" : ", ") + Degrees(a) + "°";
  return "the azimuths " + list +
         " leave part of the revolution unresolved: a periodic model through them amplifies "
         "any error in the samples " +
         FormatNumber(lebesgue, "%.0f") + "-fold (Lebesgue constant; at most " +
         FormatNumber(kMaxAzimuthLebesgueConstant, "%.0f") +
         " accepted, evenly spaced: below 3) — linearise at evenly spaced azimuths over the "
         "whole revolution (were files from another set picked?)";
}

PeriodicSystem BuildAzimuthSampledSystem(double rotor_speed, const std::vector<double>& azimuths,
                                         const std::vector<LtiSystem>& samples,
                                         SampleInterpolation interpolation) {
  if (!(rotor_speed > 0) || !std::isfinite(rotor_speed))
    throw InputError("rotor speed " + FormatNumber(rotor_speed, "%.6g") +
                     " rad/s: a sampled periodic system needs a rotor speed > 0 (a parked rotor "
                     "is time-invariant: there is no period)");
  const int K = static_cast<int>(azimuths.size());
  if (K == 0 || samples.size() != azimuths.size())
    throw InputError("azimuth-sampled system: one sample per azimuth and at least one");
  for (int k = 0; k < K; ++k) {
    if (!(azimuths[k] >= 0 && azimuths[k] < 2 * pi))
      throw InputError("azimuth " + FormatNumber(azimuths[k], "%.6g") + " rad outside [0, 2π)");
    if (k > 0 && azimuths[k] <= azimuths[k - 1])
      throw InputError("azimuths must be strictly increasing");
  }
  if (auto problem = AzimuthSamplingProblem(azimuths)) throw InputError(*problem);
  const double period = 2 * pi / rotor_speed;
  if (interpolation == SampleInterpolation::kNearestConstant) {
    if (K == 1) return PeriodicSystem::FromSamples(period, {0.0}, samples);
    // Sample k holds from the midpoint with its predecessor to the midpoint with its successor.
    std::vector<std::pair<double, int>> starts;
    for (int k = 0; k < K; ++k) {
      const double prev = k > 0 ? azimuths[k - 1] : azimuths[K - 1] - 2 * pi;
      starts.push_back({WrapAzimuth(0.5 * (prev + azimuths[k])), k});
    }
    std::sort(starts.begin(), starts.end());
    std::vector<double> times;
    std::vector<LtiSystem> ordered;
    for (const auto& [psi, k] : starts) {
      times.push_back(std::min(psi / rotor_speed, std::nextafter(period, 0.0)));
      ordered.push_back(samples[k]);
    }
    return PeriodicSystem::FromSamples(period, std::move(times), std::move(ordered));
  }
  auto series = [&](auto member) {
    std::vector<MatrixXd> m;
    for (const LtiSystem& s : samples) m.push_back(s.*member);
    return TrigInterpolant(azimuths, m);
  };
  const LtiSystem& s0 = samples.front();
  for (const LtiSystem& s : samples)
    if (s.A.rows() != s0.A.rows() || s.A.cols() != s0.A.cols() || s.B.size() != s0.B.size() ||
        s.C.size() != s0.C.size() || s.D.size() != s0.D.size())
      throw InputError("azimuth-sampled system: samples of different sizes");
  FourierMatrix a = series(&LtiSystem::A);
  FourierMatrix b = s0.B.size() ? series(&LtiSystem::B) : FourierMatrix();
  FourierMatrix c = s0.C.size() ? series(&LtiSystem::C) : FourierMatrix();
  FourierMatrix d = s0.D.size() ? series(&LtiSystem::D) : FourierMatrix();
  return PeriodicSystem::FromFourier(period, std::move(a), std::move(b), std::move(c),
                                     std::move(d));
}

PeriodicSystem BuildLinSystem(const LinOperatingPoint& op, SampleInterpolation interpolation) {
  if (!(op.rotor_speed > 0))
    throw InputError(op.files.front() + ": rotor speed " + FormatNumber(op.rotor_speed, "%.6g") +
                     " rad/s: a parked rotor is time-invariant (no period); `ltp mbc` still "
                     "gives its eigen-analysis");
  SystemLabels labels;
  for (const LinChannel& c : op.states) labels.states.push_back(c.description);
  for (const LinChannel& c : op.inputs) labels.inputs.push_back(c.description);
  for (const LinChannel& c : op.outputs) labels.outputs.push_back(c.description);
  if (op.azimuth_state) labels.rigid_body_states.push_back(*op.azimuth_state);
  try {
    labels.blades = FindBladeCoordinates(op.states).blades;
    for (size_t i = 0; i < op.states.size(); ++i)
      if (op.states[i].rotating_frame) labels.blade_states.push_back(static_cast<int>(i));
  } catch (const InputError&) {
    labels.blades = 0;  // blade states not recognised: modes are described state by state
  }
  PeriodicSystem system =
      BuildAzimuthSampledSystem(op.rotor_speed, op.azimuths, op.samples, interpolation);
  if (static_cast<int>(labels.inputs.size()) != system.inputs()) labels.inputs.clear();
  if (static_cast<int>(labels.outputs.size()) != system.outputs()) labels.outputs.clear();
  return system.WithLabels(std::move(labels)).WithRotorSpeed(op.rotor_speed);
}

std::string ModuleOf(const LinChannel& c) {
  return c.description.substr(0, c.description.find(' '));
}

std::vector<Diagnostic> LinCaveats(const LinOperatingPoint& op) {
  std::vector<Diagnostic> notes;
  const int K = op.size();
  const double hz = op.rotor_speed / (2 * pi);
  if (K == 1) {
    notes.push_back({DiagnosticCode::kAzimuthSamplesResolve, Severity::kWarning,
                     "one azimuth: the matrices are held constant over the whole revolution, so "
                     "no periodic content is resolved at all"});
  } else {
    const int H = (K - 1) / 2;
    std::string harmonics = "0";
    for (int h = 1; h <= H; ++h) harmonics += (h == H ? " and ±" : ", ±") + std::to_string(h);
    notes.push_back(
        {DiagnosticCode::kAzimuthSamplesResolve, Severity::kNote,
         std::to_string(K) + " azimuths hold only harmonics " + harmonics + " of A(ψ)" +
             (K % 2 == 0 ? " (and half of ±" + std::to_string(K / 2) + ")" : std::string()) +
             ": anything at " + std::to_string(H + 1) +
             "P and above is aliased onto them by the trigonometric interpolation or smeared by "
             "the nearest-sample hold; the two agree only as far as the samples allow, which is "
             "not a proof of convergence — linearise at more azimuths to check"});
  }
  notes.insert(notes.end(), op.diagnostics.begin(), op.diagnostics.end());
  if (op.azimuth_state) {
    notes.push_back({DiagnosticCode::kRigidBodyMode, Severity::kNote,
                     "state " + std::to_string(*op.azimuth_state + 1) + " (" +
                         op.states[*op.azimuth_state].description +
                         ") is the rotor azimuth: the rigid rotation is a Floquet exponent 0 "
                         "exactly (the trajectory's own tangent has multiplier 1); sampling moves "
                         "it slightly off 0, so the exponent nearest 0 is that rigid-body mode, "
                         "not an instability or a damped mode"});
  }
  bool rotating = false;
  for (const LinChannel& c : op.states) rotating = rotating || c.rotating_frame;
  if (rotating)
    notes.push_back(
        {DiagnosticCode::kExponentsModuloRotorSpeed, Severity::kNote,
         "exponents are defined modulo jΩ (Ω = " + FormatNumber(op.rotor_speed, "%.6g") +
             " rad/s, 1P = " + FormatNumber(hz, "%.4g") +
             " Hz): modes seen through rotating-frame states can appear shifted by "
             "±1P from a fixed-frame Campbell table (multi-blade coordinates: `--set "
             "mbc=1`, or `ltp mbc`)"});
  return notes;
}

}  // namespace ltp
