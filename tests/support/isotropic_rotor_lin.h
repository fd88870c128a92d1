#pragma once
// Rotating-frame OpenFAST `.lin` files whose exact Floquet exponents are known: a constant,
// rotationally symmetric (isotropic) model in multi-blade coordinates, transformed to blade
// coordinates at chosen azimuths.
//
// The model: `blade_dofs` second-order DOFs on each of 3 identical blades and `fixed_dofs`
// fixed-frame DOFs (in (x, y) pairs, one axial DOF when odd). In MBC coordinates
// q = (q_0, q_c, q_s per blade DOF, fixed DOFs) the matrices are constant and commute with a
// rotation of the rotor: the collectives and axial DOFs form one real block, the cyclic and
// (x, y) pairs act as a complex matrix (2×2 blocks [[p, −q], [q, p]]). Blade b's DOF is
// q_0 + q_c cos ψ_b + q_s sin ψ_b (ψ_b = ψ + 2π(b−1)/3), its rate the time derivative of that
// (rotor speed Ω constant), so x_R = T(ψ) x_MBC and A_R = (T A_MBC + Ṫ) T⁻¹: A_R(ψ) holds
// harmonics 0 and ±1 only, and its Floquet exponents are eig(A_MBC) modulo jΩ (a Lyapunov
// transformation of a constant system). The transform is written out here, not taken from
// openfast/mbc3.h, so the reference does not depend on the code under test.
//
// `gravity` adds −g cos ψ_b to each blade DOF's stiffness (per unit modal mass) in the
// rotating frame, a 1P term: the model is then no longer constant in MBC coordinates and no
// exact exponents are known, but A_R(ψ) still holds harmonics 0 and ±1 only, so three or more
// azimuths determine it and the trigonometric route in blade coordinates is exact.
#include <unistd.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ltp/openfast/linearization.h"

namespace ltp::test {

struct IsotropicRotorLin {
  Eigen::MatrixXd a_mbc;  ///< constant A in MBC coordinates
  /// eig(a_mbc): exact (without gravity) up to Eigen's eig, which does not balance: uncertain by
  /// ε‖A‖₂κ (7e-9 for the 0.05–100 Hz sets of model_size_benchmark, which use LAPACK's dgeev)
  std::vector<std::complex<double>> exponents;
  std::vector<LinFile> files;  ///< one per azimuth, blade coordinates
};

namespace isotropic_detail {

constexpr int kBlades = 3;

/// The random draws of one model, in a fixed order (a seed gives one model).
struct Draws {
  Draws(unsigned seed, bool log_spread, double lowest, double highest)
      : rng(seed),
        uniform(log_spread ? std::log(lowest) : lowest, log_spread ? std::log(highest) : highest),
        log_spread(log_spread) {}
  double Normal() { return normal(rng); }
  double Frequency() { return log_spread ? std::exp(uniform(rng)) : uniform(rng); }

  std::mt19937 rng;
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  bool log_spread;
};

/// The collective and axial DOFs `col`: K = Q diag(w²) Qᵀ, C = Q diag(2ζw) Qᵀ.
inline void RealBlock(const std::vector<int>& col, double zeta, Draws& draws, Eigen::MatrixXd& K,
                      Eigen::MatrixXd& C) {
  using Eigen::MatrixXd;
  const int m = static_cast<int>(col.size());
  MatrixXd g(m, m);
  for (int i = 0; i < g.size(); ++i) g.data()[i] = draws.Normal();
  const MatrixXd Q = g.householderQr().householderQ();
  Eigen::VectorXd w(m);
  for (int i = 0; i < m; ++i) w[i] = draws.Frequency();
  const MatrixXd k = Q * w.array().square().matrix().asDiagonal() * Q.transpose();
  const MatrixXd c = Q * (2 * zeta * w).asDiagonal() * Q.transpose();
  for (int r = 0; r < m; ++r)
    for (int s = 0; s < m; ++s) {
      K(col[r], col[s]) = k(r, s);
      C(col[r], col[s]) = c(r, s);
    }
}

/// The cyclic (cos, sin) pairs `cyc`: Hermitian stiffness and damping, plus a gyroscopic
/// (anti-Hermitian) part, written as real 2 × 2 blocks.
inline void CyclicBlock(const std::vector<std::pair<int, int>>& cyc, double zeta, Draws& draws,
                        Eigen::MatrixXd& K, Eigen::MatrixXd& C) {
  using Eigen::MatrixXcd;
  using Eigen::MatrixXd;
  const int m = static_cast<int>(cyc.size());
  MatrixXcd g(m, m);
  for (int i = 0; i < g.size(); ++i) {
    const double re = draws.Normal();
    g.data()[i] = {re, draws.Normal()};
  }
  const MatrixXcd U = g.householderQr().householderQ();
  Eigen::VectorXd w(m);
  for (int i = 0; i < m; ++i) w[i] = draws.Frequency();
  MatrixXd h(m, m);
  for (int i = 0; i < h.size(); ++i) h.data()[i] = 0.05 * draws.Normal();
  h = (h + h.transpose()).eval();
  const MatrixXcd k =
      U * w.array().square().matrix().cast<std::complex<double>>().asDiagonal() * U.adjoint();
  const MatrixXcd c = U * (2 * zeta * w).cast<std::complex<double>>().asDiagonal() * U.adjoint() +
                      std::complex<double>(0, 1) * h.cast<std::complex<double>>();
  for (int r = 0; r < m; ++r)
    for (int s = 0; s < m; ++s)
      for (auto [X, Z] : {std::pair<MatrixXd*, const MatrixXcd*>{&K, &k}, {&C, &c}}) {
        const double p = (*Z)(r, s).real(), q = (*Z)(r, s).imag();
        (*X)(cyc[r].first, cyc[s].first) = p;
        (*X)(cyc[r].first, cyc[s].second) = -q;
        (*X)(cyc[r].second, cyc[s].first) = q;
        (*X)(cyc[r].second, cyc[s].second) = p;
      }
}

/// State descriptions as ElastoDyn writes them: blade DOFs in the rotating frame, then tower.
inline std::vector<LinChannel> StateChannels(int blade_dofs, int nd) {
  const int n = 2 * nd;
  std::vector<LinChannel> states(n);
  for (int r = 0; r < n; ++r) {
    const int dof = r % nd;
    std::string what;
    if (dof < kBlades * blade_dofs) {
      // Numbered, not lettered: a set of 250 states has more blade DOFs than the alphabet.
      what = "blade dof " + std::to_string(dof / kBlades + 1) + " of blade " +
             std::to_string(dof % kBlades + 1);
      states[r].rotating_frame = true;
    } else {
      what = "tower dof " + std::to_string(dof - kBlades * blade_dofs + 1);
    }
    states[r].derivative_order = 2;
    states[r].description =
        r < nd ? "ED " + what + ", m" : "ED First time derivative of " + what + ", m/s";
  }
  return states;
}

/// A(ψ) in blade coordinates: x = T(ψ) q, so A = (T A_mbc + Ṫ) T⁻¹, plus gravity's 1P term on
/// each blade DOF. Rotating displacement (blade DOF j, blade b) at index j·N + b, MBC (j, c) at
/// 3j + c.
inline Eigen::MatrixXd RotatingFrameA(const Eigen::MatrixXd& a_mbc, int blade_dofs, double psi,
                                      double omega, double gravity) {
  using Eigen::MatrixXd;
  constexpr double pi = std::numbers::pi;
  constexpr int N = kBlades;
  const int n = static_cast<int>(a_mbc.rows()), nd = n / 2;
  MatrixXd T = MatrixXd::Identity(n, n), Td = MatrixXd::Zero(n, n);
  for (int j = 0; j < blade_dofs; ++j)
    for (int b = 0; b < N; ++b) {
      const double pb = psi + 2 * pi * b / N;
      const double t0[3] = {1, std::cos(pb), std::sin(pb)};
      const double t1[3] = {0, -std::sin(pb), std::cos(pb)};   // d/dψ
      const double t2[3] = {0, -std::cos(pb), -std::sin(pb)};  // d²/dψ²
      const int row = j * N + b;
      for (int c = 0; c < N; ++c) {
        const int m = 3 * j + c;
        T(row, m) = t0[c];
        T(nd + row, nd + m) = t0[c];
        T(nd + row, m) = omega * t1[c];
        Td(row, m) = omega * t1[c];
        Td(nd + row, nd + m) = omega * t1[c];
        Td(nd + row, m) = omega * omega * t2[c];
      }
    }
  MatrixXd a = (T * a_mbc + Td) * T.inverse();
  for (int j = 0; j < blade_dofs; ++j)
    for (int b = 0; b < N; ++b)
      a(nd + j * N + b, j * N + b) -= gravity * std::cos(psi + 2 * pi * b / N);
  return a;
}

}  // namespace isotropic_detail

/// Natural frequencies (rad/s) are drawn uniformly from [lowest, highest], or log-uniformly
/// when `log_spread` (a structure whose modes span decades: BeamDyn blades to 100 Hz).
inline IsotropicRotorLin MakeIsotropicRotorLin(int blade_dofs, int fixed_dofs,
                                               const std::vector<double>& azimuths,
                                               double omega = 1.0, unsigned seed = 1,
                                               double gravity = 0, double zeta = 0.02,
                                               double lowest = 0.5, double highest = 4.0,
                                               bool log_spread = false) {
  using namespace isotropic_detail;
  using Eigen::MatrixXd;
  const int N = kBlades, nb = blade_dofs, nf = fixed_dofs, nd = N * nb + nf, n = 2 * nd;
  const int pairs = nf / 2, axial = nf - 2 * pairs;
  Draws draws(seed, log_spread, lowest, highest);
  std::vector<int> col;
  std::vector<std::pair<int, int>> cyc;
  for (int j = 0; j < nb; ++j) col.push_back(3 * j);
  for (int i = 0; i < axial; ++i) col.push_back(N * nb + 2 * pairs + i);
  for (int j = 0; j < nb; ++j) cyc.push_back({3 * j + 1, 3 * j + 2});
  for (int k = 0; k < pairs; ++k) cyc.push_back({N * nb + 2 * k, N * nb + 2 * k + 1});
  MatrixXd K = MatrixXd::Zero(nd, nd), C = MatrixXd::Zero(nd, nd);
  RealBlock(col, zeta, draws, K, C);
  CyclicBlock(cyc, zeta, draws, K, C);
  IsotropicRotorLin out;
  out.a_mbc = MatrixXd::Zero(n, n);
  out.a_mbc.topRightCorner(nd, nd).setIdentity();
  out.a_mbc.bottomLeftCorner(nd, nd) = -K;
  out.a_mbc.bottomRightCorner(nd, nd) = -C;
  const Eigen::VectorXcd ev = out.a_mbc.eigenvalues();
  out.exponents.assign(ev.data(), ev.data() + ev.size());
  const std::vector<LinChannel> states = StateChannels(nb, nd);
  for (size_t k = 0; k < azimuths.size(); ++k) {
    LinFile f;
    f.path = "rotor." + std::to_string(k + 1) + ".lin";
    f.title = "Linearized model: isotropic rotor (tests/support/isotropic_rotor_lin.h)";
    f.rotor_speed = omega;
    f.azimuth = azimuths[k];
    f.continuous_states = n;
    f.states = states;
    f.A = RotatingFrameA(out.a_mbc, nb, azimuths[k], omega, gravity);
    out.files.push_back(std::move(f));
  }
  return out;
}

/// Gives every file of `model` (made with fixed_dofs > 0) inputs and outputs that are constant
/// in blade coordinates: a force on blade DOF a of each blade (per unit modal mass, on its
/// rate) and that DOF's displacement, plus the first tower DOF's displacement. A(ψ) is
/// unchanged, so the model's exactness in each coordinate system is too.
inline void AddBladeChannels(IsotropicRotorLin& model) {
  for (LinFile& f : model.files) {
    const int n = f.continuous_states, nd = n / 2;
    auto channel = [](const std::string& what, bool rotating) {
      LinChannel c;
      c.description = what;
      c.rotating_frame = rotating;
      return c;
    };
    f.input_channels.clear();
    f.output_channels.clear();
    f.B = Eigen::MatrixXd::Zero(n, 3);
    f.C = Eigen::MatrixXd::Zero(4, n);
    f.D = Eigen::MatrixXd::Zero(4, 3);
    for (int b = 0; b < 3; ++b) {  // blade DOF a of blade b + 1 is state b
      f.input_channels.push_back(channel("ED Blade " + std::to_string(b + 1) + " force, N", true));
      f.output_channels.push_back(
          channel("ED Blade " + std::to_string(b + 1) + " deflection, m", true));
      f.B(nd + b, b) = 1;
      f.C(b, b) = 1;
    }
    f.output_channels.push_back(channel("ED Tower deflection, m", false));
    for (int r = 0; r < nd; ++r)
      if (f.states[r].description.find("tower dof 1,") != std::string::npos) f.C(3, r) = 1;
    f.inputs = 3;
    f.outputs = 4;
  }
}

/// K evenly spaced azimuths from 0.
inline std::vector<double> EvenAzimuths(int K) {
  std::vector<double> psi;
  for (int k = 0; k < K; ++k) psi.push_back(2 * std::numbers::pi * k / K);
  return psi;
}

/// Writes the files into a fresh directory and returns its path: `dir` with this process's id
/// appended, so that tests run as parallel processes (ctest -j) never write, remove or read
/// one another's files.
inline std::string WriteLinDirectory(const std::vector<LinFile>& files, std::string dir) {
  dir.append("-").append(std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const LinFile& f : files) WriteLinFile(dir + "/" + f.path, f);
  return dir;
}

}  // namespace ltp::test
