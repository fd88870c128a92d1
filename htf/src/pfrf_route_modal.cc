// The modal route (paper eq. 42–46) as a sweep route: the modal model of the Floquet
// decomposition, one sum of modal terms per frequency.
#include <limits>
#include <optional>

#include "pfrf_route.h"

namespace ltp::internal {

namespace {

class ModalRoute : public PfrfRouteSolver {
 public:
  ModalRoute(const PfrfOptions& options, const ModalModel* model)
      : options_(options), model_(model) {
    if (model_) channel_.emplace(*model_, options_.output, options_.input);
  }

  RoutePoint Evaluate(double omega) override {
    RoutePoint p;
    const int orders = options_.max_order - options_.min_order + 1;
    if (!model_) {
      p.values.assign(orders, std::complex<double>(std::numeric_limits<double>::quiet_NaN(), 0));
      return p;
    }
    p.values = channel_->Evaluate(omega, options_.min_order, options_.max_order);
    p.ok = true;
    // The Floquet tolerance, or the Fourier tail when larger, relative to the response here.
    p.assumed_error =
        std::max(options_.floquet.integrator.rel_tol, model_->tail) * LargestFinite(p.values);
    return p;
  }
  bool concurrent() const override { return true; }  // the model is const
  std::vector<Diagnostic> Finish(const std::vector<RoutePoint>&) override {
    if (!model_)
      return {
          {DiagnosticCode::kFloquetFailed, Severity::kFailure, "modal: no Floquet decomposition"}};
    return model_->diagnostics;
  }

 private:
  const PfrfOptions& options_;
  const ModalModel* model_;
  std::optional<ModalChannel> channel_;  ///< the sweep's channel, gathered once
};

}  // namespace

std::unique_ptr<PfrfRouteSolver> MakeModalRoute(const PeriodicSystem& system,
                                                const PfrfOptions& options, PfrfResult& result) {
  if (!result.floquet.ok) return std::make_unique<ModalRoute>(options, nullptr);
  if (!result.modal) result.modal = BuildModalModel(system, result.floquet, options.modal);
  return std::make_unique<ModalRoute>(options, &*result.modal);
}

}  // namespace ltp::internal
