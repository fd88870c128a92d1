// Hill's route weighs its work before it starts (work_estimate.h): announced through the hook
// and the diagnostics, refused far beyond the limit. No assertion depends on this machine's speed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "ltp/core/error.h"
#include "ltp/floquet/work_estimate.h"
#include "ltp/hill/hill.h"
#include "support/systems.h"
#include "support/throws.h"

namespace ltp {
namespace {

using test::FastOscillator;

// Hill's dense solver weighs its eigen-solves before it starts: announced through the hook and
// the diagnostics, refused far beyond the limit (N = 1000 on 2 states: sizes 4002 and 6002,
// minutes anywhere), not weighed for a small solve. No assertion depends on this machine's speed.
TEST(WorkEstimate, DenseHillIsWeighedBeforeItStarts) {
  const PeriodicSystem system = FastOscillator(3);
  HillOptions o;
  o.solver = HillSolver::kDense;
  o.harmonics = 80;         // matrix 322: above the weighing's floor, under a second
  o.koopman_check = false;  // not needed here, and slow in an instrumented build
  o.announce_work_seconds = 0;
  int calls = 0;
  WorkEstimate seen;
  o.on_long_work = [&](const WorkEstimate& w) {
    ++calls;
    seen = w;
  };
  const HillResult r = AnalyzeHill(system, o);
  EXPECT_EQ(calls, 1);
  EXPECT_GT(seen.seconds(), 0);
  EXPECT_NE(seen.basis.find("size 322 and 482"), std::string::npos) << seen.basis;
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kWorkEstimate));
  // A small solve (matrix below 300) is not weighed at all — whatever the machine's speed (an
  // instrumented build takes seconds where a plain one takes milliseconds).
  HillOptions small = o;
  small.harmonics = 16;  // matrix 66
  calls = 0;
  AnalyzeHill(system, small);
  EXPECT_EQ(calls, 0);
  HillOptions huge = o;
  huge.harmonics = 1000;
  huge.max_work_seconds = 1e-3;  // 7e10 size³: beyond it at any speed of this century
  const std::string m = test::ThrownMessage<InputError>([&] { AnalyzeHill(system, huge); });
  EXPECT_NE(m.find("would take at least"), std::string::npos) << m;
}

// The structured solver too: N = 100 000 on Mathieu ran 29 s without a word. Its count is
// (rows at N + rows at N + Δ)·n² — 2002 + 3002 rows here — announced through the hook; and
// refused beyond the limit before any solve (N = 1e6: a 4e6-row band, minutes anywhere).
TEST(WorkEstimate, StructuredHillIsWeighedBeforeItStarts) {
  const PeriodicSystem system = FastOscillator(3);
  HillOptions o;
  o.solver = HillSolver::kStructured;
  o.harmonics = 500;  // 2002 rows: at the weighing's floor, well under a second
  o.koopman_check = false;
  o.announce_work_seconds = 0;
  int calls = 0;
  WorkEstimate seen;
  o.on_long_work = [&](const WorkEstimate& w) {
    ++calls;
    seen = w;
  };
  AnalyzeHill(system, o);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(seen.evaluations, (2002.0 + 3002.0) * 4);
  EXPECT_NE(seen.basis.find("structured"), std::string::npos) << seen.basis;
  HillOptions huge = o;
  huge.harmonics = 1000000;
  huge.max_work_seconds = 1e-3;
  const std::string m = test::ThrownMessage<InputError>([&] { AnalyzeHill(system, huge); });
  EXPECT_NE(m.find("would take at least"), std::string::npos) << m;
  EXPECT_NE(m.find("structured"), std::string::npos) << m;
}

// A convergence study is weighed as a whole before its first solve (issue: N = 1…200 dense
// showed an ETA but no estimate; 1…100 000 ran for minutes): announced once, not per
// truncation, and refused with the study's numbers before any solve.
TEST(WorkEstimate, HillStudyIsWeighedAsAWhole) {
  const PeriodicSystem system = FastOscillator(3);
  HillOptions o;
  o.solver = HillSolver::kStructured;
  o.koopman_check = false;
  o.announce_work_seconds = 0;
  int calls = 0;
  WorkEstimate seen;
  o.on_long_work = [&](const WorkEstimate& w) {
    ++calls;
    seen = w;
  };
  const HillStudy study = HillConvergenceStudy(system, 200, o);  // 2·401 rows at the largest
  EXPECT_EQ(calls, 1);
  EXPECT_FALSE(study.rows.empty());
  EXPECT_NE(seen.basis.find("truncations (N = 1…200 by the structured solver"), std::string::npos)
      << seen.basis;
  EXPECT_GT(seen.fewest_seconds(), 0);
  EXPECT_LE(seen.fewest_seconds(), seen.seconds());

  HillOptions dense = o;
  dense.solver = HillSolver::kDense;
  dense.max_work_seconds = 1e-3;
  calls = 0;
  const std::string m =
      test::ThrownMessage<InputError>([&] { HillConvergenceStudy(system, 1000, dense); });
  EXPECT_NE(m.find("the convergence study up to N = 1000 would take at least"), std::string::npos)
      << m;
  EXPECT_NE(m.find("dense solver"), std::string::npos) << m;
  EXPECT_EQ(calls, 0);  // refused before anything was announced or solved
}

}  // namespace
}  // namespace ltp
