#include "npz.h"

#include <zip.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "ltp/core/error.h"
#include "matrix_market.h"

namespace ltp::internal {

namespace {

// A member holds at most a kMatrixMarketMaxSize-square float64 matrix and its header: a larger
// size claimed by a (compressed) member is refused before anything is allocated.
constexpr std::uint64_t kMaxMemberBytes =
    std::uint64_t{8} * kMatrixMarketMaxSize * kMatrixMarketMaxSize + (std::uint64_t{1} << 20);

struct ArchiveCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};
struct MemberCloser {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};

// The .npy header's fields.
struct NpyHeader {
  std::string descr;
  bool fortran_order = false;
  std::vector<long long> shape;
};

// The value after 'key': in the header dict, up to (not including) the next top-level ',' or
// '}' (a shape tuple is taken whole).
std::string Field(const std::string& dict, const std::string& key) {
  const std::string quoted = "'" + key + "'";
  auto at = dict.find(quoted);
  if (at == std::string::npos) return {};
  at = dict.find(':', at + quoted.size());
  if (at == std::string::npos) return {};
  ++at;
  while (at < dict.size() && dict[at] == ' ') ++at;
  size_t end = at;
  if (at < dict.size() && dict[at] == '(') {
    end = dict.find(')', at);
    return end == std::string::npos ? std::string() : dict.substr(at, end - at + 1);
  }
  while (end < dict.size() && dict[end] != ',' && dict[end] != '}') ++end;
  std::string value = dict.substr(at, end - at);
  while (!value.empty() && value.back() == ' ') value.pop_back();
  return value;
}

NpyHeader ParseHeader(const std::string& dict, const std::string& where) {
  NpyHeader h;
  const std::string descr = Field(dict, "descr");
  if (descr.size() < 3 || descr.front() != '\'' || descr.back() != '\'')
    throw SceneError(where + ": no dtype ('descr') in the .npy header");
  h.descr = descr.substr(1, descr.size() - 2);
  const std::string order = Field(dict, "fortran_order");
  if (order != "True" && order != "False")
    throw SceneError(where + ": no 'fortran_order' in the .npy header");
  h.fortran_order = order == "True";
  const std::string shape = Field(dict, "shape");
  if (shape.size() < 2 || shape.front() != '(')
    throw SceneError(where + ": no 'shape' in the .npy header");
  std::string number;
  for (char c : shape.substr(1)) {
    if (c >= '0' && c <= '9') {
      number += c;
    } else if (c == ',' || c == ')') {
      if (!number.empty()) h.shape.push_back(number.size() > 9 ? -1 : std::stoll(number));
      number.clear();
    } else if (c != ' ' && c != 'L') {
      throw SceneError(where + ": shape " + shape + " is not a tuple of sizes");
    }
  }
  return h;
}

// Bytes per element and a reader to double, for the dtypes taken.
size_t ItemSize(const std::string& descr) {
  if (descr == "<f8" || descr == "<i8") return 8;
  if (descr == "<f4" || descr == "<i4") return 4;
  return 0;
}
double Element(const std::string& descr, const unsigned char* p) {
  if (descr == "<f8") {
    double x;
    std::memcpy(&x, p, 8);
    return x;
  }
  if (descr == "<f4") {
    float x;
    std::memcpy(&x, p, 4);
    return x;
  }
  if (descr == "<i8") {
    std::int64_t x;
    std::memcpy(&x, p, 8);
    return static_cast<double>(x);
  }
  std::int32_t x;
  std::memcpy(&x, p, 4);
  return x;
}

std::string Members(zip_t* z) {
  std::string list;
  const zip_int64_t n = zip_get_num_entries(z, 0);
  for (zip_int64_t i = 0; i < n && i < 20; ++i) {
    std::string name = zip_get_name(z, static_cast<zip_uint64_t>(i), 0);
    if (name.ends_with(".npy")) name.resize(name.size() - 4);
    list += (list.empty() ? "" : ", ") + name;
  }
  return list.empty() ? "none" : list;
}

}  // namespace

Eigen::MatrixXd ReadNpzArray(const std::string& path, const std::string& name) {
  CheckMatrixFile(path, ".npz archive");
  int code = 0;
  const std::unique_ptr<zip_t, ArchiveCloser> z(zip_open(path.c_str(), ZIP_RDONLY, &code));
  if (!z) throw SceneError(path + ": not a .npz (zip) archive");
  const std::string where = path + ": " + name;
  const zip_int64_t index = zip_name_locate(z.get(), (name + ".npy").c_str(), 0);
  if (index < 0)
    throw SceneError(path + ": no array '" + name + "' (the archive holds: " + Members(z.get()) +
                     ")");
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat_index(z.get(), static_cast<zip_uint64_t>(index), 0, &stat) != 0 ||
      !(stat.valid & ZIP_STAT_SIZE) || stat.size > kMaxMemberBytes)
    throw SceneError(where + ": member size unknown or beyond a " +
                     std::to_string(kMatrixMarketMaxSize) + "-square float64 matrix");
  const std::unique_ptr<zip_file_t, MemberCloser> f(
      zip_fopen_index(z.get(), static_cast<zip_uint64_t>(index), 0));
  if (!f) throw SceneError(where + ": cannot open the member (" + zip_strerror(z.get()) + ")");
  std::vector<unsigned char> bytes(static_cast<size_t>(stat.size));
  if (zip_fread(f.get(), bytes.data(), stat.size) != static_cast<zip_int64_t>(stat.size))
    throw SceneError(where + ": cannot read the member (corrupt archive?)");

  // .npy: magic, version, header length (2 bytes in version 1, 4 in 2 and 3), the header.
  if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0)
    throw SceneError(where + ": not a .npy array (no \\x93NUMPY magic)");
  const int major = bytes[6];
  size_t header_length = 0, offset = 0;
  if (major == 1) {
    header_length = bytes[8] | (static_cast<size_t>(bytes[9]) << 8);
    offset = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw SceneError(where + ": truncated .npy header");
    for (int i = 0; i < 4; ++i) header_length |= static_cast<size_t>(bytes[8 + i]) << (8 * i);
    offset = 12;
  } else {
    throw SceneError(where + ": .npy format version " + std::to_string(major) + " not read (1-3)");
  }
  if (offset + header_length > bytes.size()) throw SceneError(where + ": truncated .npy header");
  const NpyHeader h = ParseHeader(
      std::string(reinterpret_cast<const char*>(bytes.data()) + offset, header_length), where);
  offset += header_length;

  const size_t item = ItemSize(h.descr);
  if (item == 0)
    throw SceneError(where + ": dtype '" + h.descr +
                     "' not read (little-endian float64, float32, int64 or int32: a real "
                     "matrix)");
  if (h.shape.empty() || h.shape.size() > 2)
    throw SceneError(where + ": " + std::to_string(h.shape.size()) +
                     "-dimensional array, expected a matrix (2-D) or a column (1-D)");
  const long long rows = h.shape[0], cols = h.shape.size() == 2 ? h.shape[1] : 1;
  if (rows < 1 || cols < 1 || rows > kMatrixMarketMaxSize || cols > kMatrixMarketMaxSize)
    throw SceneError(where + ": size " + std::to_string(rows) + "x" + std::to_string(cols) +
                     " outside 1.." + std::to_string(kMatrixMarketMaxSize));
  const size_t count = static_cast<size_t>(rows) * static_cast<size_t>(cols);
  if (bytes.size() - offset != count * item)
    throw SceneError(where + ": " + std::to_string(bytes.size() - offset) + " data bytes for " +
                     std::to_string(rows) + "x" + std::to_string(cols) + " elements of " +
                     std::to_string(item) + " bytes");
  Eigen::MatrixXd a(rows, cols);
  for (size_t k = 0; k < count; ++k) {
    const double x = Element(h.descr, bytes.data() + offset + k * item);
    if (!std::isfinite(x))
      throw SceneError(where + ": non-finite value at element " + std::to_string(k));
    // C order walks a row first; Fortran order a column.
    const size_t r =
        h.fortran_order ? k % static_cast<size_t>(rows) : k / static_cast<size_t>(cols);
    const size_t c =
        h.fortran_order ? k / static_cast<size_t>(rows) : k % static_cast<size_t>(cols);
    a(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = x;
  }
  return a;
}

}  // namespace ltp::internal
