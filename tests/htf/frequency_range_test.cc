// Frequency and order ranges as text, channels by name, route names: the parsers the CLI and
// the Python module share. Reference: the grids are F0 + i·DF exactly (what `ltp pfrf --freq`
// always produced), so the two front ends analyse the same frequencies to the last bit.
#include "ltp/htf/frequency_range.h"

#include <gtest/gtest.h>

#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/htf/pfrf.h"

namespace ltp {
namespace {

TEST(FrequencyRange, IsStartPlusIndexTimesStep) {
  const std::vector<double> f = ParseFrequencyRange("0:450:0.6", "--freq");
  ASSERT_EQ(f.size(), 751u);  // 450 / 0.6 = 750 steps, the end included despite rounding
  for (size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i], 0 + static_cast<int>(i) * 0.6);
  EXPECT_EQ(ParseFrequencyRange("2:2:0", "freq"), std::vector<double>{2});
}

TEST(FrequencyRange, MessagesNameTheArgumentAsTheCallerSpellsIt) {
  try {
    ParseFrequencyRange("1:0:0.1", "freq");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "freq: F1 must be >= F0, got '1:0:0.1'");
  }
  try {
    ParseFrequencyRange("a:1:0.1", "--freq");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--freq F0: 'a' is not a finite number");
  }
  EXPECT_THROW(ParseFrequencyRange("0:1", "freq"), InputError);
  EXPECT_THROW(ParseFrequencyRange("0:1e7:1", "freq"), InputError);  // over a million
}

// `ltp orbit --freq`: single frequencies and ranges, comma-separated, in the order given; a range
// item is exactly ParseFrequencyRange's grid (the reference above).
TEST(FrequencyList, ItemsAreFrequenciesOrRangesInOrder) {
  EXPECT_EQ(ParseFrequencyList("0.2", "--freq"), std::vector<double>{0.2});
  EXPECT_EQ(ParseFrequencyList("0.3,0.1", "--freq"), (std::vector<double>{0.3, 0.1}));
  std::vector<double> want = ParseFrequencyRange("0:1:0.1", "--freq");
  want.push_back(1.5);
  EXPECT_EQ(ParseFrequencyList("0:1:0.1,1.5", "--freq"), want);
  try {
    ParseFrequencyList("0.1,,0.2", "--freq");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--freq: an empty item in '0.1,,0.2'");
  }
  EXPECT_THROW(ParseFrequencyList("0.1,x", "--freq"), InputError);
  EXPECT_THROW(ParseFrequencyList("nan", "--freq"), InputError);
  EXPECT_THROW(ParseFrequencyList("1:0:0.1", "--freq"), InputError);
  EXPECT_THROW(ParseFrequencyList("", "--freq"), InputError);
  EXPECT_THROW(ParseFrequencyList("0:1e6:1,2", "--freq"), InputError);  // over a million
}

TEST(OrderRange, PairsAndSingleOrders) {
  EXPECT_EQ(ParseOrderRange("-4:4", "--orders"), std::make_pair(-4, 4));
  EXPECT_EQ(ParseOrderRange("2", "orders"), std::make_pair(2, 2));
  EXPECT_THROW(ParseOrderRange("3:-3", "orders"), InputError);
  EXPECT_THROW(ParseOrderRange("0:2000", "orders"), InputError);
}

TEST(Channel, ByNameOrIndexWithTheChoicesInTheMessage) {
  const std::vector<std::string> names{"Fz_tip", "Mx"};
  EXPECT_EQ(ResolveChannel("Mx", names, 2, "input", "input"), 1);
  EXPECT_EQ(ResolveChannel("0", names, 2, "input", "input"), 0);
  try {
    ResolveChannel("2", names, 2, "--input", "input");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--input '2' is not one of the system's inputs: 0 (Fz_tip), 1 (Mx)");
  }
}

TEST(PfrfRoutes, AllIsModalCheckedByTheOtherThree) {
  PfrfOptions o;
  ASSERT_TRUE(SelectPfrfRoutes("all", &o));
  EXPECT_EQ(o.primary, PfrfRoute::kModal);
  EXPECT_EQ(o.checks,
            (std::vector<PfrfRoute>{PfrfRoute::kHtf, PfrfRoute::kShooting, PfrfRoute::kTime}));
  ASSERT_TRUE(SelectPfrfRoutes("htf", &o));
  EXPECT_EQ(o.primary, PfrfRoute::kHtf);
  EXPECT_EQ(o.checks, std::vector<PfrfRoute>{PfrfRoute::kAuto});
  EXPECT_FALSE(SelectPfrfRoutes("fast", &o));
  EXPECT_EQ(o.primary, PfrfRoute::kHtf);  // unchanged
}

}  // namespace
}  // namespace ltp
