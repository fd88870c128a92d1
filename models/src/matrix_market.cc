#include "matrix_market.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "ltp/core/error.h"

namespace ltp::internal {

namespace {

enum class Symmetry { kGeneral, kSymmetric, kSkew };

struct Header {
  bool coordinate = true;
  Symmetry symmetry = Symmetry::kGeneral;
};

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The file's lines with their numbers, past the header, without comments and blank lines.
class Lines {
 public:
  Lines(const std::string& path, std::ifstream& in) : path_(path), in_(in) {}

  bool Next(std::string& line) {
    while (std::getline(in_, line)) {
      ++number_;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '%') continue;
      return true;
    }
    return false;
  }
  [[noreturn]] void Fail(const std::string& message) const {
    throw SceneError(path_ + ":" + std::to_string(number_) + ": " + message);
  }
  void Counted() { ++number_; }

 private:
  const std::string& path_;
  std::ifstream& in_;
  int number_ = 0;
};

Header ReadHeader(Lines& lines, std::ifstream& in) {
  std::string line;
  if (!std::getline(in, line)) lines.Fail("empty file, expected a Matrix Market header");
  lines.Counted();
  std::istringstream words(line);
  std::string banner, object, format, field, symmetry;
  words >> banner >> object >> format >> field >> symmetry;
  if (banner != "%%MatrixMarket" || Lower(object) != "matrix")
    lines.Fail("expected '%%MatrixMarket matrix <format> <field> <symmetry>', got '" + line + "'");
  Header h;
  format = Lower(format);
  if (format != "coordinate" && format != "array")
    lines.Fail("format '" + format + "' is neither coordinate nor array");
  h.coordinate = format == "coordinate";
  field = Lower(field);
  if (field != "real" && field != "integer" && field != "double")
    lines.Fail("field '" + field +
               "': the matrices of a real system are real or integer (complex and pattern files "
               "cannot be used)");
  symmetry = Lower(symmetry);
  if (symmetry == "general")
    h.symmetry = Symmetry::kGeneral;
  else if (symmetry == "symmetric")
    h.symmetry = Symmetry::kSymmetric;
  else if (symmetry == "skew-symmetric")
    h.symmetry = Symmetry::kSkew;
  else
    lines.Fail("symmetry '" + symmetry + "' is not general, symmetric or skew-symmetric");
  return h;
}

// Reads exactly `count` numbers from `line` (integers for indices).
template <class T>
std::vector<T> Numbers(Lines& lines, const std::string& line, size_t count, const char* what) {
  std::istringstream in(line);
  std::vector<T> v(count);
  for (T& x : v)
    if (!(in >> x)) lines.Fail(std::string("expected ") + what + ", got '" + line + "'");
  std::string rest;
  if (in >> rest) lines.Fail(std::string("expected ") + what + " only, got '" + line + "'");
  return v;
}

void Put(Lines& lines, Eigen::MatrixXd& a, Symmetry symmetry, long i, long j, double value) {
  if (!std::isfinite(value)) lines.Fail("entry is not finite");
  a(i, j) = value;
  if (i != j && symmetry == Symmetry::kSymmetric) a(j, i) = value;
  if (i != j && symmetry == Symmetry::kSkew) a(j, i) = -value;
}

Eigen::MatrixXd ReadCoordinate(Lines& lines, const Header& h, long rows, long cols, long count) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, cols);
  std::set<std::pair<long, long>> seen;
  std::string line;
  for (long k = 0; k < count; ++k) {
    if (!lines.Next(line))
      lines.Fail("the size line announced " + std::to_string(count) + " entries, found " +
                 std::to_string(k));
    std::istringstream in(line);
    long i = 0, j = 0;
    double value = 0;
    std::string rest;
    if (!(in >> i >> j >> value) || (in >> rest))
      lines.Fail("expected 'row column value', got '" + line + "'");
    if (i < 1 || i > rows || j < 1 || j > cols)
      lines.Fail("entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the " +
                 std::to_string(rows) + " x " + std::to_string(cols) +
                 " matrix (indices start at 1)");
    if (h.symmetry != Symmetry::kGeneral && i < j)
      lines.Fail("a symmetric or skew-symmetric file stores the lower triangle only; entry (" +
                 std::to_string(i) + ", " + std::to_string(j) + ") is above the diagonal");
    if (h.symmetry == Symmetry::kSkew && i == j)
      lines.Fail("a skew-symmetric file has no diagonal entries");
    if (!seen.insert({i, j}).second)
      lines.Fail("entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is given twice");
    Put(lines, a, h.symmetry, i - 1, j - 1, value);
  }
  return a;
}

Eigen::MatrixXd ReadArray(Lines& lines, const Header& h, long rows, long cols) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, cols);
  std::string line;
  // Column by column; symmetric storage holds the lower triangle, skew the strict one.
  for (long j = 0; j < cols; ++j)
    for (long i = h.symmetry == Symmetry::kGeneral ? 0 : j + (h.symmetry == Symmetry::kSkew);
         i < rows; ++i) {
      if (!lines.Next(line))
        lines.Fail("the array ends before entry (" + std::to_string(i + 1) + ", " +
                   std::to_string(j + 1) + ")");
      Put(lines, a, h.symmetry, i, j, Numbers<double>(lines, line, 1, "one value")[0]);
    }
  return a;
}

}  // namespace

void CheckMatrixFile(const std::string& path, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw SceneError(path + ": not a readable " + what + " (missing, or not a regular file)");
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t{1} << 30;
  if (std::filesystem::file_size(path, error) > kMaxBytes)
    throw SceneError(path + ": larger than 1 GiB, more than a " +
                     std::to_string(kMatrixMarketMaxSize) + "-square matrix needs");
}

Eigen::MatrixXd ReadMatrixMarket(const std::string& path) {
  CheckMatrixFile(path, "Matrix Market file");
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open the Matrix Market file");
  Lines lines(path, in);
  const Header h = ReadHeader(lines, in);
  std::string line;
  if (!lines.Next(line)) lines.Fail("missing the size line");
  const std::vector<long> size =
      Numbers<long>(lines, line, h.coordinate ? 3 : 2,
                    h.coordinate ? "'rows columns entries'" : "'rows columns'");
  const long rows = size[0], cols = size[1];
  if (rows < 1 || cols < 1 || rows > kMatrixMarketMaxSize || cols > kMatrixMarketMaxSize)
    lines.Fail("size " + std::to_string(rows) + " x " + std::to_string(cols) + " is outside 1.." +
               std::to_string(kMatrixMarketMaxSize));
  if (h.symmetry != Symmetry::kGeneral && rows != cols)
    lines.Fail("a symmetric or skew-symmetric matrix must be square");
  if (h.coordinate && (size[2] < 0 || size[2] > rows * cols))
    lines.Fail("entry count " + std::to_string(size[2]) + " is outside 0.." +
               std::to_string(rows * cols));
  Eigen::MatrixXd a = h.coordinate ? ReadCoordinate(lines, h, rows, cols, size[2])
                                   : ReadArray(lines, h, rows, cols);
  if (lines.Next(line)) lines.Fail("data after the last entry: '" + line + "'");
  return a;
}

}  // namespace ltp::internal
