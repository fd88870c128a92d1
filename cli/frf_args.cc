#include "frf_args.h"

#include <cmath>
#include <numbers>

namespace ltp::cli {

double PhaseDeg(double re, double im) { return std::atan2(im, re) * 180 / std::numbers::pi; }

}  // namespace ltp::cli
