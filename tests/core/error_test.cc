// OptionCheck: every Validate() refuses in one style, "Owner::field = value. Violated
// constraint: constraint", with the value written exactly.
#include "ltp/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace ltp {
namespace {

template <typename Value>
std::string Refusal(std::string_view field, Value value, std::string_view constraint) {
  try {
    OptionCheck("FloquetOptions").Fail(field, value, constraint);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(OptionCheck, AnIntIsWrittenWhole) {
  EXPECT_EQ(Refusal("segments", -1, "segments >= 0 (0 = automatic)"),
            "FloquetOptions::segments = -1. Violated constraint: segments >= 0 (0 = automatic)");
  // Past six digits too (a double's "%g" would say 5e+07).
  EXPECT_EQ(Refusal("steps", 50000001L, "<= 5e7"),
            "FloquetOptions::steps = 50000001. Violated constraint: <= 5e7");
}

TEST(OptionCheck, ADoubleIsWrittenInItsShortestExactForm) {
  EXPECT_EQ(Refusal("tol", 2.0, "0 < tol < 1"),
            "FloquetOptions::tol = 2. Violated constraint: 0 < tol < 1");
  EXPECT_EQ(Refusal("tol", 1e-16, "tol >= 1e-15"),
            "FloquetOptions::tol = 1e-16. Violated constraint: tol >= 1e-15");
  // Six significant digits would print the bound it violates.
  EXPECT_EQ(Refusal("rel_tol", 0.0100000001, "0 < rel_tol < 0.01"),
            "FloquetOptions::rel_tol = 0.0100000001. Violated constraint: 0 < rel_tol < 0.01");
  EXPECT_EQ(Refusal("modes_below", INFINITY, "finite"),
            "FloquetOptions::modes_below = inf. Violated constraint: finite");
  EXPECT_EQ(Refusal("modes_below", NAN, "finite"),
            "FloquetOptions::modes_below = nan. Violated constraint: finite");
}

TEST(OptionCheck, AStringValueIsWrittenAsGiven) {
  EXPECT_EQ(Refusal("frequencies_hz", "{}", "at least one frequency"),
            "FloquetOptions::frequencies_hz = {}. Violated constraint: at least one frequency");
  EXPECT_EQ(Refusal("min_order..max_order", std::string("3..1"), "min_order <= max_order"),
            "FloquetOptions::min_order..max_order = 3..1. Violated constraint: min_order <= "
            "max_order");
}

}  // namespace
}  // namespace ltp
