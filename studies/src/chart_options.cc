#include "ltp/studies/chart_options.h"

#include <string>

#include "ltp/core/error.h"
#include "ltp/integrate/integrator_choice.h"

namespace ltp {

void ChartOptions::Validate() const {
  const OptionCheck check("ChartOptions");
  if (!(tol > 0 && tol < 1)) check.Fail("tol", tol, "0 < tol < 1");
  if (threads < 0) check.Fail("threads", threads, ">= 0 (0 = all cores)");
  if (check_every && *check_every < 0)
    check.Fail("check_every", *check_every, ">= 0 (0 = none; empty = automatic)");
  if (!(refine_tol > 0 && refine_tol < 1e-2))
    check.Fail("refine_tol", refine_tol, "0 < refine_tol < 0.01");
  campbell.Validate();
  curve.Validate();
}

IntegratorType ChartIntegrator(const ChartOptions& options, bool map, const PeriodicSystem& base) {
  if (options.integrator) return *options.integrator;
  if (!map) return IntegratorType::kRkf78;
  // Taylor: only a Fourier series can pay. Constant between breakpoints (Meissner, sampled
  // models): a product of exponentials per piece is exact. Should another point of the sweep
  // not be piecewise constant, expm's automatic step count still converges there.
  const SystemTraits traits = MeasureSystemTraits(base);
  if (traits.constant_pieces) return IntegratorType::kExpm;
  const bool taylor = base.RealSeriesA(nullptr) && TaylorSeriesPay(traits);
  return taylor ? IntegratorType::kTaylor : IntegratorType::kBulirschStoer;
}

SweepOptions ChartSweepOptions(const ChartOptions& options, bool map, const PeriodicSystem& base) {
  options.Validate();
  SweepOptions o;
  o.method = options.method;
  o.floquet.integrator.type = ChartIntegrator(options, map, base);
  o.floquet.integrator.rel_tol = options.tol;
  o.floquet.integrator.abs_tol = options.tol * 1e-3;
  o.hill_tol = options.tol;
  o.modes = !map;
  o.snapshot = options.compare && !map;
  o.check_every = options.check_every.value_or(map ? 97 : 1);
  o.threads = options.threads;
  o.Validate();
  return o;
}

BoundaryOptions ChartBoundaryOptions(const ChartOptions& options) {
  BoundaryOptions b;
  b.rel_tol = options.refine_tol;
  b.max_lines = options.refine_lines;
  b.threads = options.threads;
  b.refine = options.refine;
  return b;
}

}  // namespace ltp
