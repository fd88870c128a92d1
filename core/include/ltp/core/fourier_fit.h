#pragma once
// Time function → Fourier coefficients by FFT, with the number of harmonics chosen
// automatically to a tolerance and the truncated tail reported.
#include <string>
#include <string_view>

#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"

namespace ltp {

/// How fast the Fourier coefficients ||M_w|| fall off.
enum class FourierDecay {
  kFinite,       ///< they vanish beyond some harmonic (a trigonometric polynomial)
  kExponential,  ///< ~ a e^{−b|w|}: a smooth (analytic) function
  kAlgebraic,    ///< ~ |w|^{−p}: a jump or kink somewhere in the period
};
/// "finite", "exponential", "algebraic" (the words of the CLI's and Python's output).
std::string_view ToString(FourierDecay decay);

struct FourierFitOptions {
  /// Keep harmonics until the norm of everything dropped is below tol · max_w ||M_w||.
  double tol = 1e-12;
  /// Upper bound on FFT samples per period (a power of two). Discontinuous functions decay
  /// only like 1/w and hit this bound: the tail is then reported, not hidden.
  int max_samples = 1 << 14;
  /// Never keep more than this many harmonics (0 = limited by max_samples only).
  int max_harmonics = 0;
};

struct FourierFit {
  FourierMatrix series;
  int samples = 0;         ///< FFT length that was finally used
  double tail = 0;         ///< estimated norm of the dropped harmonics, relative to max ||M_w||
  bool converged = false;  ///< tail <= tol
  FourierDecay decay = FourierDecay::kFinite;
  double decay_rate = 0;  ///< b in ||M_w|| ~ a e^{-b|w|} (exponential) or p in ~ |w|^{-p}
};

/// FFT fit of a T-periodic rows×cols function.
FourierFit FitFourier(const PeriodicSystem::MatrixFunction& f, int rows, int cols, double period,
                      const FourierFitOptions& options = {});

/// Fourier coefficients of A, B, C, D of a system; exact (copied) for Fourier-form systems.
struct SystemFourier {
  FourierFit A, B, C, D;
};
SystemFourier ToFourier(const PeriodicSystem& system, const FourierFitOptions& options = {});

/// A Fourier-form copy of the system (labels and rotor speed kept).
PeriodicSystem ToFourierSystem(const PeriodicSystem& system, const FourierFitOptions& options = {});

}  // namespace ltp
