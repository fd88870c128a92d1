#pragma once
// Multi-blade coordinates (Coleman transform; W. Johnson, "Helicopter Theory" (1980), §12.3;
// K. H. Hohenemser & S.-K. Yin, "Some applications of the method of multiblade coordinates",
// J. AHS 17(3), 1972). For N blades at ψ_i = Ωt + 2π(i−1)/N:
//
//   ζ_i = ζ_0 + Σ_{n=1..K} (ζ_nc cos nψ_i + ζ_ns sin nψ_i) [+ ζ_d (−1)^i for even N],
//   K = (N−1)/2 (odd N) or (N−2)/2 (even N),
//
// with inverse ζ_0 = (1/N)Σζ_i, ζ_nc = (2/N)Σζ_i cos nψ_i, ζ_ns = (2/N)Σζ_i sin nψ_i,
// ζ_d = (1/N)Σζ_i(−1)^i.
//
// Which channel belongs to which blade is read from its label as OpenFAST does (BladeDigit).
#include <Eigen/Dense>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ltp {

/// T(ψ): blade angles = T(ψ) · MBC coordinates, N × N, ψ = azimuth of blade 1. Columns in the
/// order of MbcCoordinateNames. dψ_order = 1 or 2 gives dT/dψ, d²T/dψ². @throws InputError for
/// N < 3.
Eigen::MatrixXd MbcTransform(int blades, double psi, int dpsi_order = 0);

/// "zeta_0", "zeta_1c", "zeta_1s", ..., and "zeta_d" for even N.
std::vector<std::string> MbcCoordinateNames(int blades);

/// Position of the blade number (one digit) in a channel description, by OpenFAST's patterns
/// in its order (matlab-toolbox findBladeTriplets.m, openfast_toolbox linfile.py): "blade N",
/// "blade root N", "BD_N", "bN", "bladeN", "PitchBearingN", else the first digit.
std::optional<size_t> BladeDigit(const std::string& description);

}  // namespace ltp
