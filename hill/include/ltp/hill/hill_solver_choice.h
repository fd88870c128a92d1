#pragma once
// Automatic choice of Hill's eigensolver (HillSolver::kAuto), from the same traits as the
// integrator choice and the work–precision study's crossovers.
#include <string>

#include "ltp/hill/hill.h"
#include "ltp/integrate/integrator_choice.h"

namespace ltp {

struct HillSolverChoice {
  HillSolver solver = HillSolver::kDense;
  std::string reason;
};

/// Structured (banded shift-invert) when its cost model n·(band/m)²·0.5 ≤ 1 × dense (m =
/// (2N+1)n rows, band = (min(H_A, 2N)+1)n) and m ≥ 50, or whenever max|Re eig A_0| > 10 Ωp (the
/// dense selection missed stiff.yaml's +150 exponent at every N; shift-invert around A_0's
/// eigenvalues found it); dense otherwise. `coefficient_harmonics` = H_A of the series used.
HillSolverChoice ChooseHillSolver(const SystemTraits& traits, int harmonics,
                                  int coefficient_harmonics);

}  // namespace ltp
