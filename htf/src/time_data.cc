#include "ltp/htf/time_data.h"

#include <cmath>

#include "ltp/core/error.h"

namespace ltp {

void TimeData::Validate() const {
  if (!(period > 0) || !std::isfinite(period))
    throw InputError("time data: period " + std::to_string(period) + " s (must be finite and > 0)");
  if (records.empty()) throw InputError("time data: no records");
  for (size_t r = 0; r < records.size(); ++r) {
    const TimeRecord& rec = records[r];
    const std::string where = "record " + std::to_string(r + 1);
    const Eigen::Index n = static_cast<Eigen::Index>(rec.time.size());
    if (n < 2) throw InputError(where + ": fewer than 2 samples");
    if (rec.inputs.rows() != n || rec.outputs.rows() != n)
      throw InputError(where + ": " + std::to_string(n) + " times but " +
                       std::to_string(rec.inputs.rows()) + " input and " +
                       std::to_string(rec.outputs.rows()) + " output samples");
    if (r > 0 && (rec.inputs.cols() != records[0].inputs.cols() ||
                  rec.outputs.cols() != records[0].outputs.cols()))
      throw InputError(where + ": other channels than record 1");
    if (!rec.inputs.allFinite() || !rec.outputs.allFinite())
      throw InputError(where + ": holds a value that is not finite (NaN or inf)");
    const double dt = (rec.time.back() - rec.time.front()) / static_cast<double>(n - 1);
    if (!(dt > 0) || !std::isfinite(dt)) throw InputError(where + ": times do not increase");
    for (Eigen::Index i = 1; i < n; ++i) {
      const double step = rec.time[static_cast<size_t>(i)] - rec.time[static_cast<size_t>(i - 1)];
      if (!(std::abs(step - dt) <= 1e-6 * dt))
        throw InputError(where + ": unequal sampling at sample " + std::to_string(i + 1) +
                         " (step " + std::to_string(step) + " s, mean " + std::to_string(dt) +
                         " s): a gap or a jitter");
    }
  }
}

}  // namespace ltp
