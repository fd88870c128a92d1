#include "scene_file_matrices.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "ltp/core/error.h"

namespace ltp::internal {

FourierMatrix FileMatrixSeries(const FileMatrix& m,
                               const std::function<double(const ExpressionEntry&)>& value) {
  int top = 0;
  for (const FileMatrixTerm& term : m.terms)
    for (const auto& h : term.harmonics) top = std::max(top, h.order);
  FourierMatrix series(m.rows, m.cols, top);
  for (const FileMatrixTerm& term : m.terms) {
    const double factor = term.factor ? value(*term.factor) : 1.0;
    if (!std::isfinite(factor))
      throw SceneError(term.factor->where + ": factor '" + term.factor->text + "' is not finite");
    if (term.constant.size()) series[0] += factor * term.constant.cast<std::complex<double>>();
    // C cos(wΩt) + S sin(wΩt) = (C − jS)/2 e^{jwΩt} + (C + jS)/2 e^{−jwΩt}.
    for (const auto& h : term.harmonics) {
      Eigen::MatrixXcd c = Eigen::MatrixXcd::Zero(m.rows, m.cols);
      if (h.cos.size()) c += 0.5 * factor * h.cos.cast<std::complex<double>>();
      if (h.sin.size())
        c -= h.sin.cast<std::complex<double>>() * std::complex<double>(0, 0.5 * factor);
      series[h.order] += c;
      series[-h.order] += c.conjugate();
    }
  }
  return series;
}

}  // namespace ltp::internal
