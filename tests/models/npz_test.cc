// The .npz reader on archives written here byte by byte with libzip: the .npy layout (magic,
// version, header dict, data) as numpy's format documentation (numpy.lib.format) gives it, so
// every refusal can be reached. tests/python/test_npz.py checks it against numpy's own writer.
#include "npz.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zip.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ltp/core/error.h"
#include "support/throws.h"

namespace ltp {
namespace {

using internal::ReadNpzArray;

// A .npy member: version 1.0, the header padded with spaces to a multiple of 64 bytes.
std::string Npy(const std::string& dict, const std::string& data, int major = 1) {
  std::string header = dict;
  const size_t fixed = major == 1 ? 10 : 12;
  while ((fixed + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += static_cast<char>(major);
  out += '\0';
  const size_t length = header.size();
  out += static_cast<char>(length & 0xff);
  out += static_cast<char>((length >> 8) & 0xff);
  if (major != 1) out += std::string(2, '\0');
  return out + header + data;
}

std::string Doubles(const std::vector<double>& v) {
  std::string out(v.size() * 8, '\0');
  std::memcpy(out.data(), v.data(), out.size());
  return out;
}

std::string Archive(const std::vector<std::pair<std::string, std::string>>& members) {
  const std::string path = ::testing::TempDir() + "ltp-" + std::to_string(getpid()) + "-t.npz";
  std::filesystem::remove(path);
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  EXPECT_NE(z, nullptr);
  std::vector<std::string> keep;  // libzip reads the buffers when the archive is closed
  keep.reserve(members.size());
  for (const auto& [name, bytes] : members) {
    keep.push_back(bytes);
    zip_source_t* s = zip_source_buffer(z, keep.back().data(), keep.back().size(), 0);
    EXPECT_GE(zip_file_add(z, (name + ".npy").c_str(), s, ZIP_FL_OVERWRITE), 0);
  }
  EXPECT_EQ(zip_close(z), 0);
  return path;
}

std::string Refusal(const std::string& path, const std::string& name) {
  return test::ThrownMessage<SceneError>([&] { ReadNpzArray(path, name); });
}

TEST(Npz, ReadsCAndFortranOrderAndColumns) {
  const std::vector<double> values = {1, 2, 3, 4, 5, 6};
  const std::string path = Archive(
      {{"C", Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", Doubles(values))},
       {"F", Npy("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", Doubles(values), 2)},
       {"v",
        Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }", Doubles({7, 8, 9}))}});
  Eigen::MatrixXd c(2, 3), f(2, 3);
  c << 1, 2, 3, 4, 5, 6;  // C order: a row after another
  f << 1, 3, 5, 2, 4, 6;  // Fortran order: a column after another
  EXPECT_EQ(ReadNpzArray(path, "C"), c);
  EXPECT_EQ(ReadNpzArray(path, "F"), f);
  EXPECT_EQ(ReadNpzArray(path, "v"), Eigen::Vector3d(7, 8, 9));
}

TEST(Npz, RefusesWhatIsNotARealMatrix) {
  const std::string ok = "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2), }";
  const std::string two = Doubles({1, 2});
  const std::string path = Archive(
      {{"good", Npy(ok, two)},
       {"magic", "NUMPY not really"},
       {"version", Npy(ok, two, 4)},
       {"short", Npy(ok, two.substr(0, 12))},
       {"complex", Npy("{'descr': '<c16', 'fortran_order': False, 'shape': (1, 2), }", two)},
       {"cube", Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 1, 2), }", two)},
       {"scalar", Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (), }", two)},
       {"huge", Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (99999, 2), }", two)},
       {"noshape", Npy("{'descr': '<f8', 'fortran_order': False, }", two)},
       {"nan", Npy(ok, Doubles({1, std::numeric_limits<double>::quiet_NaN()}))}});
  EXPECT_EQ(ReadNpzArray(path, "good"), Eigen::RowVector2d(1, 2));
  const std::pair<const char*, const char*> cases[] = {
      {"magic", "not a .npy array"},
      {"version", ".npy format version 4 not read"},
      {"short", "12 data bytes for 1x2 elements of 8 bytes"},
      {"complex", "dtype '<c16' not read"},
      {"cube", "3-dimensional array"},
      {"scalar", "0-dimensional array"},
      {"huge", "size 99999x2 outside 1..4096"},
      {"noshape", "no 'shape'"},
      {"nan", "non-finite value at element 1"},
      {"missing", "no array 'missing' (the archive holds: good, magic, version"}};
  for (const auto& [name, why] : cases)
    EXPECT_NE(Refusal(path, name).find(why), std::string::npos)
        << name << ": " << Refusal(path, name);
  // Not an archive, and not a regular file.
  const std::string text = ::testing::TempDir() + "ltp-" + std::to_string(getpid()) + "-t.txt";
  {
    std::FILE* f = std::fopen(text.c_str(), "w");
    std::fputs("plain text", f);
    std::fclose(f);
  }
  EXPECT_NE(Refusal(text, "K").find("not a .npz (zip) archive"), std::string::npos);
  EXPECT_NE(Refusal(::testing::TempDir(), "K")
                .find("not a readable .npz archive (missing, or not a regular file)"),
            std::string::npos);
}

}  // namespace
}  // namespace ltp
