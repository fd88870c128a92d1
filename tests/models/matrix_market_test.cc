// The Matrix Market reader against matrices written out by hand in each storage the format
// allows (coordinate and array; general, symmetric, skew-symmetric), and one clear refusal for
// each kind of bad file. SciPy's own files (scipy.io.mmwrite) are read in
// tests/python/test_matrix_market.py.
#include "matrix_market.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "ltp/core/error.h"

namespace ltp::internal {
namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "ltp_mm_" + name + ".mtx";
  std::ofstream(path) << text;
  return path;
}

Eigen::MatrixXd Read(const std::string& name, const std::string& text) {
  return ReadMatrixMarket(Write(name, text));
}

TEST(MatrixMarket, CoordinateGeneralWithComments) {
  const Eigen::MatrixXd a = Read("general",
                                 "%%MatrixMarket matrix coordinate real general\n"
                                 "% written by hand\n"
                                 "2 3 3\n"
                                 "1 1 1.5\n"
                                 "2 3 -2e3\n"
                                 "\n"
                                 "1 2 7\n");
  Eigen::MatrixXd expected(2, 3);
  expected << 1.5, 7, 0, 0, 0, -2e3;
  EXPECT_EQ(a, expected);
}

TEST(MatrixMarket, SymmetricAndSkewStorageAreMirrored) {
  Eigen::MatrixXd symmetric(3, 3);
  symmetric << 4, 1, 0, 1, 5, 2, 0, 2, 6;
  EXPECT_EQ(Read("sym",
                 "%%MatrixMarket matrix coordinate real symmetric\n3 3 5\n"
                 "1 1 4\n2 1 1\n2 2 5\n3 2 2\n3 3 6\n"),
            symmetric);
  // Array storage: the lower triangle column by column (scipy's dense symmetric files).
  EXPECT_EQ(Read("symarray",
                 "%%MatrixMarket matrix array real symmetric\n3 3\n"
                 "4\n1\n0\n5\n2\n6\n"),
            symmetric);
  Eigen::MatrixXd skew(2, 2);
  skew << 0, -3, 3, 0;
  EXPECT_EQ(Read("skew", "%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 3\n"),
            skew);
  EXPECT_EQ(Read("skewarray", "%%MatrixMarket matrix array real skew-symmetric\n2 2\n3\n"), skew);
}

TEST(MatrixMarket, ArrayGeneralIsColumnMajorAndIntegersRead) {
  Eigen::MatrixXd expected(2, 2);
  expected << 1, 3, 2, 4;
  EXPECT_EQ(Read("array", "%%MatrixMarket matrix array integer general\n2 2\n1\n2\n3\n4\n"),
            expected);
}

TEST(MatrixMarket, BadFilesAreRefusedWithTheirLine) {
  struct Bad {
    const char* name;
    std::string text;
    std::string says;
  };
  const std::string head = "%%MatrixMarket matrix coordinate real general\n";
  for (const Bad& b : std::vector<Bad>{
           {"empty", "", "empty file"},
           {"banner", "%MatrixMarket matrix coordinate real general\n1 1 0\n", "expected"},
           {"complex", "%%MatrixMarket matrix coordinate complex general\n1 1 0\n", "complex"},
           {"pattern", "%%MatrixMarket matrix coordinate pattern general\n1 1 0\n", "pattern"},
           {"hermitian", "%%MatrixMarket matrix coordinate real hermitian\n1 1 0\n", "hermitian"},
           {"nosize", head, "missing the size line"},
           {"huge", head + "100000 100000 1\n", "outside 1..4096"},
           {"outside", head + "2 2 1\n3 1 1\n", ":3: entry (3, 1) is outside"},
           {"zero", head + "2 2 1\n0 1 1\n", "indices start at 1"},
           {"twice", head + "2 2 2\n1 1 1\n1 1 2\n", ":4: entry (1, 1) is given twice"},
           {"short", head + "2 2 2\n1 1 1\n", "announced 2 entries, found 1"},
           {"extra", head + "2 2 1\n1 1 1\n2 2 2\n", "data after the last entry"},
           {"nan", head + "1 1 1\n1 1 nan\n", "expected 'row column value'"},
           {"inf", head + "1 1 1\n1 1 1e999\n", "expected 'row column value'"},
           {"upper", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n",
            "above the diagonal"},
           {"notsquare", "%%MatrixMarket matrix coordinate real symmetric\n2 3 0\n",
            "must be square"},
           {"words", head + "2 2 1\n1 1 one\n", "expected 'row column value'"},
           {"arrayshort", "%%MatrixMarket matrix array real general\n2 1\n1\n",
            "ends before entry (2, 1)"},
       }) {
    SCOPED_TRACE(b.name);
    try {
      Read(b.name, b.text);
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(b.says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("ltp_mm_" + std::string(b.name)), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(ReadMatrixMarket(::testing::TempDir() + "ltp_mm_missing.mtx"), SceneError);
  // Not a regular file: refused before reading (/dev/zero has no end of line to wait for).
  EXPECT_THROW(ReadMatrixMarket("/dev/zero"), SceneError);
  EXPECT_THROW(ReadMatrixMarket(::testing::TempDir()), SceneError);
}

}  // namespace
}  // namespace ltp::internal
