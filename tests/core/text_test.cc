// Text helpers: diagnostics said once with a count, whatever numbers they carry.
#include "ltp/core/text.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ltp {
namespace {

TEST(CollapseRepeatedLines, SameSentenceWithOtherNumbersIsSaidOnceWithACount) {
  std::vector<std::string> lines = {"integrator auto → bs: smooth"};
  for (int k = 0; k < 1000; ++k)
    lines.push_back("segment " + std::to_string(k) + " [" + std::to_string(0.001 * k) +
                    ", 1e-3]: step size underflow at t = " + std::to_string(k * 1.5e-7));
  lines.push_back("eigenvalues of the monodromy failed: INFO = 3");
  const std::vector<std::string> out = CollapseRepeatedLines(lines);
  ASSERT_EQ(out.size(), 1u + 3u + 1u + 1u);
  EXPECT_EQ(out[0], lines[0]);
  EXPECT_EQ(out[1], lines[1]);
  EXPECT_EQ(out[3], lines[3]);
  EXPECT_EQ(out[4], "… and 997 more like the above");
  EXPECT_EQ(out[5], lines.back());
}

TEST(CollapseRepeatedLines, ShortGroupsAndDistinctLinesAreKept) {
  // Four of one shape: a summary line would save nothing, so all four stay.
  const std::vector<std::string> four = {
      "mode 1 tie",          "mode 2 tie", "mode 3 tie", "mode 4 tie", "Liouville residual 1e-12",
      "a different sentence"};
  EXPECT_EQ(CollapseRepeatedLines(four), four);
  // Exponents in numbers belong to the number: 1e-5 and 2.5e+3 have one shape.
  const std::vector<std::string> numbers = {"x = 1e-5", "x = 2.5e+3", "x = 7", "x = -4", "x = 1"};
  EXPECT_EQ(CollapseRepeatedLines(numbers, 2).size(), 3u + 1u);  // "x = -#" is another shape
}

}  // namespace
}  // namespace ltp

namespace ltp {
namespace {

// n separators give n + 1 parts, empty ones included: a reader that counts cells against its
// header sees a trailing separator as an empty cell, and an option list sees an empty item.
TEST(SplitAt, EverySeparatorCutsEmptyPartsIncluded) {
  using V = std::vector<std::string>;
  EXPECT_EQ(SplitAt("a,,b,", ','), (V{"a", "", "b", ""}));
  EXPECT_EQ(SplitAt(",a", ','), (V{"", "a"}));
  EXPECT_EQ(SplitAt("", ','), (V{""}));
  EXPECT_EQ(SplitAt("0:10:0.5", ':'), (V{"0", "10", "0.5"}));
  EXPECT_EQ(SplitAt(" x ; y", ';'), (V{" x ", " y"}));  // no trimming
}

}  // namespace
}  // namespace ltp
