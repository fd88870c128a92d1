// The chart journal's records read back as they were written (chart_journal.h): a point's
// diagnostics keep their code and severity, not only their text, and a record that names a code
// beyond the list is not a diagnostic. Reference: the values written.
#include "chart_journal.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ltp::cli {
namespace {

// The payloads of records framed by the writer (FramedPayloads reads the frames back).
std::vector<std::string> Payloads(const std::string& records) { return FramedPayloads(records); }

TEST(ChartJournal, DiagnosticsKeepTheirCodeAndSeverity) {
  SweepPoint p;
  p.index = 7;
  p.ok = true;
  p.verdict = StabilityVerdict::kMarginal;
  p.values = {0.5};
  p.diagnostics = {
      {DiagnosticCode::kStabilityMarginal, Severity::kWarning, "stability undecided"},
      {DiagnosticCode::kIntegratorChosen, Severity::kNote, "integrator auto → taylor"}};
  PointWriter writer;
  const std::string first = writer.Records(p, false);
  const std::string again = writer.Records(p, false);  // the diagnostics are written once
  PointReader reader;
  std::vector<SweepPoint> read;
  for (const std::string& records : {first, again})
    for (const std::string& payload : Payloads(records))
      if (auto point = reader.Read(payload)) read.push_back(*point);
  ASSERT_EQ(Payloads(first).size(), 3u);  // two 'D' records, then the point
  ASSERT_EQ(Payloads(again).size(), 1u);
  ASSERT_EQ(read.size(), 2u);
  for (const SweepPoint& q : read) {
    EXPECT_EQ(q.index, 7u);
    EXPECT_EQ(q.verdict, StabilityVerdict::kMarginal);
    ASSERT_EQ(q.diagnostics.size(), 2u);
    for (size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(q.diagnostics[k].code, p.diagnostics[k].code);
      EXPECT_EQ(q.diagnostics[k].severity, p.diagnostics[k].severity);
      EXPECT_EQ(q.diagnostics[k].text, p.diagnostics[k].text);
    }
  }
}

TEST(ChartJournal, ADiagnosticBeyondTheListOfCodesIsRefused) {
  SweepPoint p;
  p.diagnostics = {{DiagnosticCode::kCount, Severity::kNote, "not a code"}};
  PointWriter writer;
  PointReader reader;
  const std::vector<std::string> payloads = Payloads(writer.Records(p, false));
  ASSERT_EQ(payloads.size(), 2u);
  EXPECT_FALSE(reader.Read(payloads[0]));  // the 'D' record: not remembered
  EXPECT_FALSE(reader.Read(payloads[1]));  // so the point refers to a diagnostic never seen
}

}  // namespace
}  // namespace ltp::cli
