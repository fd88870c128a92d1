#pragma once
// Internal: matrices of a scene file's second_order block read from Matrix Market files, as a
// finite-element package writes them — each a sum of terms
//   factor · (C + Σ_w C_w^cos cos(w Ωp t) + C_w^sin sin(w Ωp t)),   Ωp = 2π/T,
// with `factor` an expression in the parameters (e.g. Omega for a gyroscopic matrix). The sum
// is an exact Fourier series, so the scene is a Fourier-form system (docs/cli-reference.md,
// "scene files").
#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "expression_matrix.h"
#include "ltp/core/fourier_matrix.h"

namespace ltp::internal {

struct FileMatrixTerm {
  struct Harmonic {
    int order = 1;
    Eigen::MatrixXd cos, sin;  ///< empty: zero
  };
  std::optional<ExpressionEntry> factor;  ///< parameters only; absent: 1
  Eigen::MatrixXd constant;               ///< empty: zero
  std::vector<Harmonic> harmonics;
};

struct FileMatrix {
  std::vector<FileMatrixTerm> terms;
  int rows = 0, cols = 0;
  std::string where;  ///< "scene.yaml:12: second_order.K", for messages at build time
};

/// The sum of the terms as a Fourier series; `value` evaluates a term's factor.
FourierMatrix FileMatrixSeries(const FileMatrix& m,
                               const std::function<double(const ExpressionEntry&)>& value);

}  // namespace ltp::internal
