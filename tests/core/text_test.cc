// Text helpers: the splitter and the UTF-8 check of the readers.
#include "ltp/core/text.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ltp {
namespace {}  // namespace
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
