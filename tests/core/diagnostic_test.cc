#include "ltp/core/diagnostic.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace ltp {
namespace {

// Python shows the codes by these names: each must be there, distinct and snake_case.
TEST(Diagnostic, EveryCodeHasADistinctSnakeCaseName) {
  std::set<std::string> names;
  for (DiagnosticCode code : AllDiagnosticCodes()) {
    const std::string name(CodeName(code));
    ASSERT_FALSE(name.empty());
    EXPECT_NE(name, "unknown");
    for (char c : name) EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_');
    EXPECT_TRUE(names.insert(name).second) << name << " twice";
  }
  // The list holds every code: one per value below the kCount sentinel.
  EXPECT_EQ(AllDiagnosticCodes().size(), static_cast<size_t>(DiagnosticCode::kCount));
}

TEST(Diagnostic, HasCodeAndTexts) {
  const std::vector<Diagnostic> d = {
      {DiagnosticCode::kStatesBalanced, Severity::kNote, "states rescaled"},
      {DiagnosticCode::kLiouvilleCheckFailed, Severity::kFailure, "Liouville check failed"}};
  EXPECT_TRUE(HasCode(d, DiagnosticCode::kLiouvilleCheckFailed));
  EXPECT_FALSE(HasCode(d, DiagnosticCode::kModesUnderResolved));
  EXPECT_EQ(Texts(d), (std::vector<std::string>{"states rescaled", "Liouville check failed"}));
}

// Lines as diagnostics of one code: the grouping is then by the texts' shape alone.
std::vector<Diagnostic> OfOneCode(const std::vector<std::string>& lines) {
  std::vector<Diagnostic> d;
  for (const std::string& l : lines)
    d.push_back({DiagnosticCode::kSegmentIntegrationFailed, Severity::kFailure, l});
  return d;
}

TEST(Diagnostic, CollapseRepeatedSaysTheSameSentenceWithOtherNumbersOnceWithACount) {
  std::vector<std::string> lines = {"integrator auto → bs: smooth"};
  for (int k = 0; k < 1000; ++k)
    lines.push_back("segment " + std::to_string(k) + " [" + std::to_string(0.001 * k) +
                    ", 1e-3]: step size underflow at t = " + std::to_string(k * 1.5e-7));
  lines.push_back("eigenvalues of the monodromy failed: INFO = 3");
  const std::vector<std::string> out = Texts(CollapseRepeated(OfOneCode(lines)));
  ASSERT_EQ(out.size(), 1u + 3u + 1u + 1u);
  EXPECT_EQ(out[0], lines[0]);
  EXPECT_EQ(out[1], lines[1]);
  EXPECT_EQ(out[3], lines[3]);
  EXPECT_EQ(out[4], "… and 997 more like the above");
  EXPECT_EQ(out[5], lines.back());
}

TEST(Diagnostic, CollapseRepeatedKeepsShortGroupsAndDistinctLines) {
  // Four of one shape: a summary line would save nothing, so all four stay.
  const std::vector<std::string> four = {
      "mode 1 tie",          "mode 2 tie", "mode 3 tie", "mode 4 tie", "Liouville residual 1e-12",
      "a different sentence"};
  EXPECT_EQ(Texts(CollapseRepeated(OfOneCode(four))), four);
  // Exponents in numbers belong to the number: 1e-5 and 2.5e+3 have one shape.
  const std::vector<std::string> numbers = {"x = 1e-5", "x = 2.5e+3", "x = 7", "x = -4", "x = 1"};
  EXPECT_EQ(CollapseRepeated(OfOneCode(numbers), 2).size(), 3u + 1u);  // "x = -#" is another shape
}

// Per code: the count line keeps the group's code and severity.
TEST(Diagnostic, CollapseRepeatedKeepsTheGroupsCode) {
  std::vector<Diagnostic> d;
  for (int i = 0; i < 6; ++i)
    d.push_back({DiagnosticCode::kSegmentIntegrationFailed, Severity::kFailure,
                 "segment [" + std::to_string(i) + ", " + std::to_string(i + 1) + "]: NaN"});
  d.push_back({DiagnosticCode::kSegmentRefinementStopped, Severity::kWarning, "stopped"});
  const std::vector<Diagnostic> out = CollapseRepeated(d);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[3].text, "… and 3 more like the above");
  EXPECT_EQ(out[3].code, DiagnosticCode::kSegmentIntegrationFailed);
  EXPECT_EQ(out[3].severity, Severity::kFailure);
  EXPECT_EQ(out[4].code, DiagnosticCode::kSegmentRefinementStopped);
}

}  // namespace
}  // namespace ltp
