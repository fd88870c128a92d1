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
  // The list holds every value: the last enumerator's index + 1 values.
  EXPECT_EQ(AllDiagnosticCodes().size(), static_cast<size_t>(DiagnosticCode::kMatrixDropped) + 1);
}

TEST(Diagnostic, HasCodeAndTexts) {
  const std::vector<Diagnostic> d = {
      {DiagnosticCode::kStatesBalanced, Severity::kNote, "states rescaled"},
      {DiagnosticCode::kLiouvilleCheckFailed, Severity::kFailure, "Liouville check failed"}};
  EXPECT_TRUE(HasCode(d, DiagnosticCode::kLiouvilleCheckFailed));
  EXPECT_FALSE(HasCode(d, DiagnosticCode::kModesUnderResolved));
  EXPECT_EQ(Texts(d), (std::vector<std::string>{"states rescaled", "Liouville check failed"}));
}

// As CollapseRepeatedLines, per code: the count line keeps the group's code and severity.
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
