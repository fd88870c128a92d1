// The error estimate's sources in words (ltp/floquet/estimate_source.h).
#include "ltp/floquet/estimate_source.h"

namespace ltp {

std::string_view EstimateSource(ErrorEstimateMethod method, IntegratorType integrator) {
  if (method != ErrorEstimateMethod::kLocalErrors)
    return "difference to the run at the requested tolerance on another grid; the numbers shown "
           "come from the refined, 100× tighter run";
  switch (integrator) {
    case IntegratorType::kTaylor:
      return "difference to the product of the steps' order-p sums; the numbers shown come from "
             "order p + 4 on the same steps";
    case IntegratorType::kBulirschStoer:
      return "its steps' local errors, one extrapolation order lower, carried to the exponents; "
             "the numbers come from that one run";
    default:  // the Magnus methods choosing their own steps
      return "difference to the pass at half the steps that chose them; the numbers shown come "
             "from the finer pass";
  }
}

std::string_view EstimateSourceBrief(ErrorEstimateMethod method, IntegratorType integrator) {
  if (method != ErrorEstimateMethod::kLocalErrors) return "";
  switch (integrator) {
    case IntegratorType::kTaylor:
      return "from its order-p product";
    case IntegratorType::kBulirschStoer:
      return "from its steps' local errors";
    default:
      return "from its pass at half the steps";
  }
}

}  // namespace ltp
