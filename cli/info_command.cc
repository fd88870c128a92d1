#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "command.h"
#include "format.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/models/tower_rotor.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

struct InfoArgs {
  SceneArgs scene;
  double at = 0;  ///< snapshot time
  bool json = false;
};

int RunInfo(const InfoArgs& args) {
  LoadedScene l = LoadSceneArgs(args.scene);
  const PeriodicSystem& sys = l.system;
  FourierFitOptions fit_options;
  fit_options.tol = 1e-10;
  const SystemFourier fourier = ToFourier(sys, fit_options);
  const LtiSystem snap = sys.Snapshot(args.at);
  Eigen::VectorXcd eig =
      snap.A.size() ? Eigen::VectorXcd(snap.A.eigenvalues()) : Eigen::VectorXcd();
  std::vector<std::complex<double>> ev(eig.data(), eig.data() + eig.size());
  std::sort(ev.begin(), ev.end(), [](auto a, auto b) {
    return std::abs(a.imag()) != std::abs(b.imag()) ? std::abs(a.imag()) < std::abs(b.imag())
                                                    : a.imag() > b.imag();
  });
  const char* form = sys.form() == PeriodicSystem::Form::kFourier             ? "Fourier series"
                     : sys.form() == PeriodicSystem::Form::kPiecewiseConstant ? "piecewise constant"
                                                                              : "time function";
  auto fit_json = [](const FourierFit& f) {
    return json{{"harmonics", f.series.max_harmonic()},
                {"converged", f.converged},
                {"tail", JsonNumber(f.tail)},
                {"decay", std::string(ToString(f.decay))},
                {"decay_rate", JsonNumber(f.decay_rate)}};
  };
  if (args.json) {
    json j = {{"scene", l.scene.name},
              {"parameters", ParametersJson(l.parameters)},
              {"states", sys.states()},
              {"inputs", sys.inputs()},
              {"outputs", sys.outputs()},
              {"period", sys.period()},
              {"omega_p", sys.omega()},
              {"form", form},
              {"breakpoints", sys.breakpoints()},
              {"harmonics",
               {{"A", fit_json(fourier.A)},
                {"B", fit_json(fourier.B)},
                {"C", fit_json(fourier.C)},
                {"D", fit_json(fourier.D)}}},
              {"snapshot_time", args.at}};
    json e = json::array();
    for (auto z : ev)
      e.push_back({{"re", JsonNumber(z.real())},
                   {"im", JsonNumber(z.imag())},
                   {"frequency_hz", JsonNumber(z.imag() / (2 * kPi))}});
    j["snapshot_eigenvalues"] = e;
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "scene       " << l.scene.name << " (" << l.scene.source << ")\n"
            << "            " << l.scene.description << "\n"
            << "parameters  " << ParameterList(l.parameters) << "\n"
            << "size        " << sys.states() << " states, " << sys.inputs() << " inputs, "
            << sys.outputs() << " outputs\n"
            << "period      T = " << Num(sys.period(), 10) << " s   (Ωp = " << Num(sys.omega(), 10)
            << " rad/s, fp = " << Num(sys.omega() / (2 * kPi), 8) << " Hz)\n"
            << "form        " << form;
  if (!sys.breakpoints().empty()) {
    std::cout << ", jumps at t =";
    for (double b : sys.breakpoints()) std::cout << " " << Num(b, 8);
  }
  std::cout << "\nharmonics   (to relative tolerance " << fit_options.tol << ")\n";
  auto row = [](const char* name, const FourierFit& f) {
    std::cout << "    " << name << ": " << f.series.max_harmonic() << " harmonics, decay "
              << ToString(f.decay);
    if (f.decay == FourierDecay::kExponential)
      std::cout << " (rate " << Num(f.decay_rate, 3) << " per harmonic)";
    if (f.decay == FourierDecay::kAlgebraic)
      std::cout << " (|A_w| ~ |w|^-" << Num(f.decay_rate, 3) << ")";
    std::cout << (f.converged ? "" : ", NOT converged: dropped tail " + Num(f.tail, 2)) << "\n";
  };
  row("A", fourier.A);
  if (sys.inputs()) row("B", fourier.B);
  if (sys.outputs()) row("C", fourier.C);
  if (l.scene.name == "tower-rotor") {
    const TowerRotorModel model = BuildTowerRotorModel(TowerRotorParams::FromMap(l.parameters));
    std::cout << "reduction   " << model.reduction.Summary() << "\n"
              << "non-rotating modes (Ω = 0, blades along ±z) beside the paper's table (§5.1):\n"
              << "      #  model [Hz]  FE [Hz]  paper FEM  paper MBS   this model's mode shape\n";
    for (const TowerRotorMode& m : TowerRotorModeTable(l.parameters))
      std::cout << "    " << std::setw(3) << m.index << Num(m.frequency_hz, 5, 12)
                << Num(m.fe_frequency_hz, 5, 9)
                << (m.paper_fem_hz > 0 ? Num(m.paper_fem_hz, 4, 11) : std::string(11, ' '))
                << (m.paper_mbs_hz > 0 ? Num(m.paper_mbs_hz, 4, 11) : std::string(11, ' ')) << "   "
                << m.description << "\n";
  }
  std::cout << "snapshot eigenvalues at t = " << args.at
            << " (frozen LTI system; not the Floquet exponents):\n";
  for (auto z : ev)
    std::cout << "    " << Num(z.real(), 8, 14) << " " << (z.imag() < 0 ? "-" : "+") << " "
              << Num(std::abs(z.imag()), 8, 12) << " j    (" << Num(z.imag() / (2 * kPi), 6)
              << " Hz)\n";
  return 0;
}

}  // namespace

Command AddInfoCommand(CLI::App& app) {
  static InfoArgs args;
  args = InfoArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "info", "describe a scene: sizes, period, harmonic content, snapshot eigenvalues");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--at", args.at, "time of the snapshot (s)")->capture_default_str();
  cmd->add_flag("--json", args.json, "machine-readable output on stdout");
  return {cmd, [] { return RunInfo(args); }};
}

}  // namespace ltp::cli
