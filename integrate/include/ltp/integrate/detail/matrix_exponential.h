#pragma once
// e^a for the n × n exponentials of the exponential integrators (Magnus, Magnus–Filon, exact
// pieces): Higham's scaling and squaring with Padé degrees 3…13 (SIAM J. Matrix Anal. Appl. 26
// (2005); the algorithm of Eigen's MatrixExponential), its products in BLAS (MultiplyInto) and
// its solve in LAPACK, where Eigen's own kernels are compiled for baseline x86-64
// (docs/magnus-filon.md, "Where the time goes"). A real matrix is balanced first (a diagonal
// of powers of two, exact) where that lowers its 1-norm enough to save squarings, as Al-Mohy
// and Higham's 2009 algorithm does.
#include <Eigen/Core>

namespace ltp::internal {

/// out = e^a; out must not overlap a.
void ExpInto(const Eigen::Ref<const Eigen::MatrixXd>& a, Eigen::Ref<Eigen::MatrixXd> out);
void ExpInto(const Eigen::Ref<const Eigen::MatrixXcd>& a, Eigen::Ref<Eigen::MatrixXcd> out);

/// Whether ExpInto balances (it does through LAPACK; the Eigen-only build of the sanitizers
/// scales and squares the matrix as given).
bool ExpBalances();

}  // namespace ltp::internal
