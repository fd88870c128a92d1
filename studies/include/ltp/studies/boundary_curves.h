#pragma once
// Stability boundaries of a 2-D map as curves, traced by continuation from the refined boundary
// points (stability_boundary.h) — docs/stability-boundaries.md, "Curves by continuation".
//
// A boundary where a real Floquet multiplier crosses σ = +1 or σ = −1 is a root of
//   D_σ(p) = det(Φ(p) − σI) = Π_k (ρ_k − σ),
// real for a real Φ, smooth, and changing sign as one real multiplier crosses σ. Both edges of a
// parametric-resonance tongue are such roots, damped or not. Each curve point is a bracketed 1-D
// root of D_σ across the curve (TOMS 748), at the next point a tangent predictor proposes; the
// step adapts to the corrector's displacement and the turning of the curve; a curve ends at the
// map's edges or where it closes. Where the two edges of an undamped tongue come closer than
// the evaluations resolve (towards the tip), D_σ no longer changes sign beyond its own error:
// the point then brackets both edges together (`merged`), it does not invent a value.
//
// A boundary of another kind (a complex pair crossing the unit circle) stays as its refined
// points; the result says how many and why.
//
// Time-reversible systems without damping (half_period_blocks.h; undamped Hill equations) are
// traced through the half-period factorization instead: each edge of a tongue is then a simple
// root of one block's determinant, resolved to the integration's accuracy down to the tip.
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "ltp/floquet/floquet.h"
#include "ltp/studies/stability_boundary.h"
#include "ltp/studies/sweep.h"

namespace ltp {

/// Which multiplier crossing a boundary curve follows.
enum class BoundaryKind {
  kRealPlusOne,   ///< a real multiplier crosses +1 (a T-periodic solution on the curve)
  kRealMinusOne,  ///< a real multiplier crosses −1 (a 2T-periodic solution on the curve)
  kComplex,       ///< a complex pair crosses the unit circle (not traced)
};
std::string_view ToString(BoundaryKind kind);

/// For a time-reversible system without damping (half_period_blocks.h): the symmetry of the
/// periodic solution on a curve, x(−t) = R x(t) (even) or −R x(t) (odd). The curve is then the
/// root of one half-period block's determinant; kNone: of D_σ.
enum class BoundarySymmetry { kNone, kEven, kOdd };
std::string_view ToString(BoundarySymmetry symmetry);

/// D_σ = Π_k (ρ_k − σ) as sign and log|·|, from log multipliers (any branch): no overflow or
/// underflow for multipliers of any size. `log_error`: the error of each log ρ_k (an exponent's
/// error estimate × T); `log_abs_error` is then the first-order bound of D_σ's error,
/// log Σ_k |ρ_k| ε Π_{j≠k} |ρ_j − σ| (−∞ when log_error is 0).
struct CharacteristicValue {
  int sign = 0;  ///< −1, 0 or +1 (0: some ρ_k = σ exactly)
  double log_abs = -std::numeric_limits<double>::infinity();
  double log_abs_error = -std::numeric_limits<double>::infinity();
};
CharacteristicValue MultiplierDeterminant(const std::vector<std::complex<double>>& log_multipliers,
                                          int sigma, double log_error = 0);

/// det M as sign and log|·| (LU with partial pivoting). Given `error`, entrywise bounds of M's
/// error (M's shape), `log_abs_error` bounds det's error (Ipsen & Rehman, SIAM J. Matrix Anal.
/// Appl. 30, 2008): |det(M + E) − det M| ≤ Σ_{k=1}^{m} s_{m−k} ‖E‖₂^k, s_j the j-th elementary
/// symmetric function of M's singular values, ‖E‖₂ ≤ ‖E‖_F plus the LU's own backward error
/// 8 m ε σmax. No first-order cut: two singular values near zero (a double root) keep their
/// second-order term.
CharacteristicValue BlockDeterminant(const Eigen::MatrixXd& block,
                                     const Eigen::MatrixXd* error = nullptr);

struct BoundaryCurveOptions {
  /// The 1-D root across the curve stops at a bracket below rel_tol × max(|p|, 1e-3 · span)
  /// (the evaluations' own error usually dominates the reported bracket).
  double rel_tol = 1e-11;
  /// Steps along the curve, as fractions of the map's diagonal in units of each axis's span.
  double initial_step = 0.002, min_step = 1e-6, max_step = 0.01;
  /// Corrector displacement (fraction of the step) and turning per step (radians) above which
  /// a step is rejected and halved.
  double max_displacement = 0.15, max_turn = 0.3;
  int max_points = 4000;  ///< per curve, both directions together
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct BoundaryCurve {
  BoundaryKind kind = BoundaryKind::kRealPlusOne;
  BoundarySymmetry symmetry = BoundarySymmetry::kNone;
  /// Along the curve: both swept parameters per point, in grid-axis order.
  std::vector<std::array<double, 2>> points;
  /// Per point: the axis the 1-D root was solved along (the other is held fixed) and the bound:
  /// the boundary crosses that line within ±bracket of the point (the root's final bracket
  /// plus the offset the evaluation's own error estimate allows).
  std::vector<int> across;
  std::vector<double> bracket;
  /// Per point: the two edges of a tongue are closer than the evaluations resolve; the bracket
  /// holds both (towards an undamped tongue's tip).
  std::vector<char> merged;
  std::array<std::string, 2> end_notes;  ///< why each end stopped (first point's end first)
  int evaluations = 0;
};

struct BoundaryCurves {
  std::vector<BoundaryCurve> curves;
  /// Refined boundary points not on a curve (complex crossings, or a seed that failed), with why.
  std::vector<size_t> untraced;
  std::vector<std::string> untraced_notes;
  int evaluations = 0;
};

/// Traces the boundaries through `boundary` (RefineBoundaryPoints of the same map) as curves.
/// `sweep`, `options`: as for RefineBoundaryPoints (the evaluations' tolerance). 2-D maps only
/// (empty otherwise).
BoundaryCurves TraceBoundaryCurves(const Scene& scene, const ParameterMap& base,
                                   const SweepGrid& grid,
                                   const std::vector<BoundaryPoint>& boundary,
                                   const SweepOptions& sweep, const BoundaryOptions& options,
                                   const BoundaryCurveOptions& curve_options = {});

}  // namespace ltp
