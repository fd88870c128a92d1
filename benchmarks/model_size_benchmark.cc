// Real model sizes (docs/model-sizes.md): how the cost of a Floquet analysis grows with the number
// of states and with the fastest mode, and where it stands against the peer a user would write.
//
//   build/benchmarks/model_size_benchmark                      # every row
//   build/benchmarks/model_size_benchmark --benchmark_filter=SampledRotor/124
//
// SampledRotor/STATES/RATIO  `ltp floquet` on an OpenFAST set as the command runs it (scene, the
//     analysis, the model-error term of docs/sampled-models.md): a rotor written at 3 azimuths
//     (tests/support/isotropic_rotor_lin.h, with a gravity-like 1P blade term), STATES states,
//     its fastest mode RATIO × 1P (600: a BeamDyn blade mode near 100 Hz at 10 rpm). Counter
//     `evaluations`: of A(t)·Φ in all the analyses, the work the time follows.
// IsotropicTurbineExact/STATES  the same without gravity: exact exponents (LAPACK's balanced
//     eig of the constant multi-blade matrix), the largest true error against the estimate.
// FeRotorVersusScipy/ELEMENTS  the finite-element rotor of tests/python/fe_rotor.py in SI units
//     (8·(ELEMENTS+1) states) through the Python module, against SciPy's DOP853 on the n × n
//     matrix ODE (benchmarks/peers/fe_rotor_peer.py), each in its own process; counters give
//     both CPU times and their ratio (> 1: ltp cheaper), and the two max Re λ.
#include <benchmark/benchmark.h>
#include <lapacke.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "ltp/floquet/floquet.h"
#include "ltp/floquet/model_error.h"
#include "ltp/integrate/threads.h"
#include "ltp/models/scene_input.h"
#include "support/isotropic_rotor_lin.h"

namespace {

const bool kSingleThreadedBlas = ltp::UseSingleThreadedBlas();  // as the ltp command runs

void SampledRotor(benchmark::State& state) {
  const int states = static_cast<int>(state.range(0)), ratio = static_cast<int>(state.range(1));
  // 2 (3 blade_dofs + 2) states; modes drawn in [0.5, 4] rad/s, so Ω = 4 / ratio; the 1P term
  // 0.01 (1/s²) is about 1 % of the blade stiffness, as gravity is for a 60 m blade.
  const int blade_dofs = (states / 2 - 2) / 3;
  const double omega = 4.0 / ratio;
  const auto model =
      ltp::test::MakeIsotropicRotorLin(blade_dofs, 2, ltp::test::EvenAzimuths(3), omega, 1, 0.01);
  const std::string dir = ltp::test::WriteLinDirectory(
      model.files, (std::filesystem::temp_directory_path() /
                    ("ltp-rotor-" + std::to_string(states) + "-" + std::to_string(ratio)))
                       .string());
  long evaluations = 0;
  double max_real = 0, estimate = 0;
  for (auto _ : state) {
    const ltp::LoadedScene l = ltp::LoadSceneInput({dir}, {});
    ltp::FloquetResult r = ltp::AnalyzeFloquet(l.system);
    ltp::IncludeModelError(l.model_alternatives, ltp::FloquetOptions{}, r);
    evaluations = r.rhs_evals;
    max_real = r.max_real_exponent;
    estimate = r.error_estimate.value_or(-1);
  }
  state.counters["states"] = 2 * (3 * blade_dofs + 2);
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["max_real"] = max_real;
  state.counters["estimate"] = estimate;
}
BENCHMARK(SampledRotor)
    ->Args({28, 600})
    ->Args({64, 600})
    ->Args({124, 600})
    ->Args({64, 25})
    ->Args({64, 100})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// A wind-turbine-like set: natural frequencies 0.3…630 rad/s (0.05–100 Hz) spread
// log-uniformly, 10 rpm, a gravity-like 1P term of 0.2 1/s² (≈ 1 % of a first flap mode's
// stiffness), 3 azimuths; the analysis of the modes below CUTOFF_CENTIHZ/100 Hz (0 = all),
// model-error term included, as `ltp floquet --modes-below` runs it.
// The turbine-like set of about `states` states (natural frequencies 0.3…630 rad/s
// log-uniformly, 10 rpm, 3 azimuths, the 1P term `gravity`) and the directory its files are
// written to.
struct TurbineSet {
  ltp::test::IsotropicRotorLin model;
  std::string dir;
  int states = 0;
};
constexpr double kTurbineSpeed = 2 * std::numbers::pi / 6;  // 10 rpm

TurbineSet WriteTurbineSet(int states, double gravity, const std::string& name) {
  const int blade_dofs = (states / 2 - 2) / 3;
  TurbineSet t;
  t.model = ltp::test::MakeIsotropicRotorLin(blade_dofs, 2, ltp::test::EvenAzimuths(3),
                                             kTurbineSpeed, 3, gravity, 0.02, 0.3, 630.0, true);
  t.dir = ltp::test::WriteLinDirectory(
      t.model.files,
      (std::filesystem::temp_directory_path() / (name + "-" + std::to_string(states))).string());
  t.states = 2 * (3 * blade_dofs + 2);
  return t;
}

void SampledTurbineModesBelow(benchmark::State& state) {
  const double cutoff_hz = state.range(1) / 100.0;
  const TurbineSet set = WriteTurbineSet(static_cast<int>(state.range(0)), 0.2, "ltp-turbine");
  const std::string& dir = set.dir;
  ltp::FloquetOptions o;
  o.modes_below = 2 * std::numbers::pi * cutoff_hz;
  long evaluations = 0;
  int kept = 0;
  double max_real = 0, estimate = 0;
  for (auto _ : state) {
    const ltp::LoadedScene l = ltp::LoadSceneInput({dir}, {});
    ltp::FloquetResult r = ltp::AnalyzeFloquet(l.system, o);
    ltp::IncludeModelError(l.model_alternatives, o, r);
    evaluations = r.rhs_evals;
    max_real = r.max_real_exponent;
    estimate = r.error_estimate.value_or(-1);
    kept = r.reduction ? r.reduction->kept : r.states;
  }
  state.counters["states"] = set.states;
  state.counters["kept"] = kept;
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["max_real"] = max_real;
  state.counters["estimate"] = estimate;
}
BENCHMARK(SampledTurbineModesBelow)
    ->Args({64, 300})
    ->Args({64, 0})
    ->Args({124, 0})
    ->Args({252, 0})
    ->Args({124, 300})
    ->Args({252, 300})
    ->Args({504, 300})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// The same set without the gravity-like term (an isotropic rotor: constant in multi-blade
// coordinates, so its exact exponents are the eigenvalues of A_MBC modulo jΩ,
// isotropic_rotor_lin.h), every mode: counters `true_error` (the largest distance of a computed
// exponent to the nearest reference one, imaginary parts modulo Ω) and `estimate` (the
// analysis's own, model error included), which must be at least the true error. The reference
// is LAPACK's dgeev, which balances A first: Eigen's unbalanced eig (the `exponents` of the
// test model) is uncertain by ε‖A‖₂κ_k ≈ 7e-9 for the fast modes of these sets (‖A‖₂ = 2.6e5,
// eigenvalue conditions κ up to 260), and differed from dgeev's by 1.4e-10–2.8e-9, above the
// estimates — where ltp's exponents and dgeev's agreed to 2e-11 at 64 and 124 states.
std::vector<std::complex<double>> BalancedEigenvalues(Eigen::MatrixXd a) {
  const lapack_int n = static_cast<lapack_int>(a.rows());
  std::vector<double> re(static_cast<size_t>(n)), im(static_cast<size_t>(n));
  double unused = 0;
  if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n, a.data(), n, re.data(), im.data(), &unused, 1,
                    &unused, 1) != 0)
    return {};
  std::vector<std::complex<double>> e;
  for (lapack_int k = 0; k < n; ++k) e.emplace_back(re[k], im[k]);
  return e;
}

void IsotropicTurbineExact(benchmark::State& state) {
  const TurbineSet set = WriteTurbineSet(static_cast<int>(state.range(0)), 0, "ltp-isotropic");
  const std::vector<std::complex<double>> reference = BalancedEigenvalues(set.model.a_mbc);
  double true_error = 0, estimate = 0;
  for (auto _ : state) {
    const ltp::LoadedScene l = ltp::LoadSceneInput({set.dir}, {});
    ltp::FloquetResult r = ltp::AnalyzeFloquet(l.system, ltp::FloquetOptions{});
    ltp::IncludeModelError(l.model_alternatives, ltp::FloquetOptions{}, r);
    estimate = r.error_estimate.value_or(-1);
    if (reference.empty()) {
      state.SkipWithError("LAPACK's dgeev failed on A_MBC");
      break;
    }
    true_error = 0;
    for (const ltp::FloquetMode& m : r.modes) {
      double nearest = HUGE_VAL;
      for (const std::complex<double> e : reference)
        nearest = std::min(nearest,
                           std::hypot(m.exponent.real() - e.real(),
                                      std::remainder(m.exponent.imag() - e.imag(), kTurbineSpeed)));
      true_error = std::max(true_error, nearest);
    }
  }
  state.counters["states"] = set.states;
  state.counters["true_error"] = true_error;
  state.counters["estimate"] = estimate;
}
BENCHMARK(IsotropicTurbineExact)
    ->Arg(64)
    ->Arg(124)
    ->Arg(252)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

nlohmann::json RunPeer(int elements, const char* which, std::string* error) {
  const std::string script = std::string(LTP_SOURCE_DIR) + "/benchmarks/peers/fe_rotor_peer.py";
  const std::string command = "PYTHONPATH=" + std::string(LTP_BINARY_DIR) +
                              "/python /usr/bin/python3 " + script + " " +
                              std::to_string(elements) + " " + which + " 2>&1";
  FILE* p = popen(command.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  while (p && fgets(buf.data(), buf.size(), p)) out += buf.data();
  if ((p ? pclose(p) : -1) != 0) {
    *error = std::string(which) + " peer unavailable: " + out;
    return {};
  }
  // The peer's one JSON object is its last line (stderr is merged for the messages above).
  while (!out.empty() && out.back() == '\n') out.pop_back();
  const size_t line = out.rfind('\n');
  nlohmann::json j =
      nlohmann::json::parse(line == std::string::npos ? out : out.substr(line + 1), nullptr, false);
  if (j.is_discarded()) *error = std::string(which) + " peer wrote no JSON: " + out;
  return j;
}

void FeRotorVersusScipy(benchmark::State& state) {
  const int elements = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::string error;
    const nlohmann::json ltp = RunPeer(elements, "ltp", &error);
    const nlohmann::json scipy =
        error.empty() ? RunPeer(elements, "scipy", &error) : nlohmann::json{};
    if (!error.empty()) {
      state.SkipWithError(error.c_str());
      return;
    }
    state.SetIterationTime(ltp["wall_s"].get<double>());
    state.counters["states"] = ltp["states"].get<double>();
    state.counters["ltp_cpu_s"] = ltp["cpu_s"].get<double>();
    state.counters["scipy_cpu_s"] = scipy["cpu_s"].get<double>();
    state.counters["cpu_ratio"] = scipy["cpu_s"].get<double>() / ltp["cpu_s"].get<double>();
    state.counters["wall_ratio"] = scipy["wall_s"].get<double>() / ltp["wall_s"].get<double>();
    state.counters["ltp_max_real"] = ltp["max_real"].get<double>();
    state.counters["scipy_max_real"] = scipy["max_real"].get<double>();
    state.counters["ltp_estimate"] = ltp["estimate"].get<double>();
  }
}
BENCHMARK(FeRotorVersusScipy)
    ->Arg(4)
    ->Arg(9)
    ->Arg(14)
    ->Arg(19)  // 160 states: SciPy's solve takes about two minutes
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
