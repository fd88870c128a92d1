#pragma once
// What `ltp pfrf` and `ltp snapshot` share beyond the library's parsers of frequency and order
// ranges (ltp/htf/frequency_range.h) and channels (ltp/core/channel.h): the phase of the CSV
// columns.
#include <string>

namespace ltp::cli {

/// Phase in degrees, (−180, 180].
double PhaseDeg(double re, double im);
}  // namespace ltp::cli
