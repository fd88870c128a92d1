#include "ltp/floquet/half_period_blocks.h"

#include <vector>

#include "time_reversal.h"

namespace ltp {

namespace {

// R's +1 and −1 states when R is diagonal with as many of each and μ = 0.
struct Split {
  std::vector<Eigen::Index> plus, minus;
};

std::optional<Split> SplitOf(const PeriodicSystem& system) {
  const std::optional<internal::TimeReversal> reversal = internal::FindTimeReversal(system);
  if (!reversal || reversal->rate != 0) return std::nullopt;
  const Eigen::MatrixXd& r = reversal->involution;
  if (!r.isDiagonal(0.0)) return std::nullopt;
  Split s;
  for (Eigen::Index i = 0; i < r.rows(); ++i) (r(i, i) > 0 ? s.plus : s.minus).push_back(i);
  if (s.plus.size() != s.minus.size()) return std::nullopt;
  return s;
}

}  // namespace

const Eigen::MatrixXd& HalfPeriodBlocks::Factor(int sigma, bool even) const {
  if (sigma > 0) return even ? U : Q;
  return even ? P : W;
}

bool HasHalfPeriodBlocks(const PeriodicSystem& system) { return SplitOf(system).has_value(); }

std::optional<HalfPeriodBlocks> ComputeHalfPeriodBlocks(const PeriodicSystem& system,
                                                        const IntegratorOptions& integrator) {
  const std::optional<Split> split = SplitOf(system);
  if (!split) return std::nullopt;
  const TransitionResult half = StateTransition(system, 0, 0.5 * system.period(), integrator);
  if (!half.ok || !half.phi.allFinite()) return std::nullopt;
  const auto& phi = half.phi;
  return HalfPeriodBlocks{phi(split->plus, split->plus), phi(split->plus, split->minus),
                          phi(split->minus, split->plus), phi(split->minus, split->minus)};
}

}  // namespace ltp
