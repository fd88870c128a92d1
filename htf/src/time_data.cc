#include "ltp/htf/time_data.h"

#include <algorithm>
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
    if (rec.inputs.rows() != n || rec.outputs.rows() != n ||
        (rec.auxiliary.cols() > 0 && rec.auxiliary.rows() != n))
      throw InputError(where + ": " + std::to_string(n) + " times but " +
                       std::to_string(rec.inputs.rows()) + " input and " +
                       std::to_string(rec.outputs.rows()) + " output samples");
    if (!rec.angle.empty() && rec.angle.size() != rec.time.size())
      throw InputError(where + ": " + std::to_string(n) + " times but " +
                       std::to_string(rec.angle.size()) + " angles");
    if (r > 0 && (rec.inputs.cols() != records[0].inputs.cols() ||
                  rec.outputs.cols() != records[0].outputs.cols()))
      throw InputError(where + ": other channels than record 1");
    if (!rec.inputs.allFinite() || !rec.outputs.allFinite() || !rec.auxiliary.allFinite())
      throw InputError(where + ": holds a value that is not finite (NaN or inf)");
    // Sums of squares must stay in the double range (least squares, spectra, noise power).
    constexpr double kLargest = 1e150;
    for (const Eigen::MatrixXd* m : {&rec.inputs, &rec.outputs, &rec.auxiliary})
      if (m->size() > 0 && m->cwiseAbs().maxCoeff() > kLargest)
        throw InputError(where + ": a value of magnitude " +
                         MessageNumber(m->cwiseAbs().maxCoeff(), 3) +
                         " — sums of squares would overflow; rescale the channel (units)");
    if (!(rec.time_error >= 0) || !std::isfinite(rec.time_error))
      throw InputError(where + ": time_error " + MessageNumber(rec.time_error, 3) +
                       " s (must be finite and >= 0)");
    for (double a : rec.angle)
      if (!std::isfinite(a)) throw InputError(where + ": an angle is not finite");
    for (Eigen::Index i = 1; i < n; ++i) {
      const double step = rec.time[static_cast<size_t>(i)] - rec.time[static_cast<size_t>(i - 1)];
      if (!(step > 0) || !std::isfinite(step))
        throw InputError(where + ": times do not increase at sample " + std::to_string(i + 1) +
                         " (t = " + MessageNumber(rec.time[static_cast<size_t>(i)], 10) + " s)");
    }
  }
}

double SamplingStep(const TimeRecord& record) {
  std::vector<double> steps;
  for (size_t i = 1; i < record.time.size(); ++i)
    steps.push_back(record.time[i] - record.time[i - 1]);
  if (steps.empty()) return 0;
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

void RequireUniformSampling(const TimeRecord& record, const std::string& where, double tolerance) {
  const double dt = SamplingStep(record);
  for (size_t i = 1; i < record.time.size(); ++i) {
    const double step = record.time[i] - record.time[i - 1];
    if (!(std::abs(step - dt) <= tolerance * dt))
      throw InputError(where + ": unequal sampling at sample " + std::to_string(i + 1) + " (t = " +
                       MessageNumber(record.time[i], 10) + " s: step " + MessageNumber(step, 6) +
                       " s, the record's " + MessageNumber(dt, 6) + " s): a gap or a jitter");
  }
}

}  // namespace ltp
