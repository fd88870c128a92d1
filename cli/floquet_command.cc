#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <nlohmann/json.hpp>

#include "command.h"
#include "format.h"
#include "ltp/core/error.h"
#include "ltp/floquet/floquet.h"
#include "plot.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

struct FloquetArgs {
  SceneArgs scene;
  FloquetOptions options;
  std::string integrator = "dopri5";
  std::string segments = "auto";
  std::string multipliers = "schur";
  bool json = false;
  std::string modes_csv;
  std::string plot;
};

// Turns the string options into the library's enums and counts. @throws InputError.
void ResolveOptions(FloquetArgs& args) {
  auto type = ParseIntegratorType(args.integrator);
  if (!type)
    throw InputError("unknown integrator '" + args.integrator +
                     "' (dopri5, rkf78, cvode, cvode-adams, magnus4, magnus6, expm)");
  args.options.integrator.type = *type;
  if (args.segments == "auto") {
    args.options.segments = 0;
  } else {
    try {
      size_t used = 0;
      args.options.segments = std::stoi(args.segments, &used);
      if (used != args.segments.size() || args.options.segments < 1) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw InputError("--segments must be a positive integer or 'auto', got '" + args.segments + "'");
    }
  }
  if (args.multipliers == "schur" || args.multipliers == "periodic-schur") {
    args.options.multipliers = MultiplierMethod::kPeriodicSchur;
  } else if (args.multipliers == "single-shot") {
    args.options.multipliers = MultiplierMethod::kSingleShot;
  } else {
    throw InputError("--multipliers must be 'schur' or 'single-shot', got '" + args.multipliers + "'");
  }
}

int RunFloquet(FloquetArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // reject a bad extension up front
  ResolveOptions(args);
  LoadedScene l = LoadSceneArgs(args.scene);
  const FloquetResult r = AnalyzeFloquet(l.system, args.options);
  const double T = r.period;

  if (!args.modes_csv.empty()) {
    std::ofstream csv(args.modes_csv);
    if (!csv) throw InputError("cannot write '" + args.modes_csv + "'");
    csv << "t";
    for (int k = 0; k < r.states; ++k)
      for (int i = 0; i < r.states; ++i) csv << ",re_xi" << k << "_" << i << ",im_xi" << k << "_" << i;
    csv << "\n" << std::setprecision(12);
    for (size_t s = 0; s < r.mode_samples.size(); ++s) {
      csv << r.sample_times[s];
      for (int k = 0; k < r.states; ++k)
        for (int i = 0; i < r.states; ++i)
          csv << "," << r.mode_samples[s](i, k).real() << "," << r.mode_samples[s](i, k).imag();
      csv << "\n";
    }
  }
  if (!args.plot.empty()) PlotFloquet(r, l.scene.name, args.plot);

  if (args.json) {
    json exps = json::array(), mults = json::array(), modes = json::array();
    for (const FloquetMode& m : r.modes) {
      exps.push_back({{"re", JsonNumber(m.exponent.real())}, {"im", JsonNumber(m.exponent.imag())},
                      {"frequency_hz", JsonNumber(m.frequency_hz)},
                      {"damping_ratio", JsonNumber(m.damping_ratio)}});
      const double mag = ExpClamped(m.log_multiplier.real());
      mults.push_back({{"re", JsonNumber(mag * std::cos(m.log_multiplier.imag()))},
                       {"im", JsonNumber(mag * std::sin(m.log_multiplier.imag()))},
                       {"log_abs", JsonNumber(m.log_multiplier.real())},
                       {"arg", JsonNumber(m.log_multiplier.imag())}});
      modes.push_back({{"branch", m.branch}, {"central_weight", JsonNumber(m.central_weight)},
                       {"branch_margin", JsonNumber(m.branch_margin)},
                       {"eigenvector_residual", JsonNumber(m.eigvec_residual)}});
    }
    json j = {{"scene", l.scene.name},
              {"parameters", ParametersJson(l.parameters)},
              {"states", r.states},
              {"period", T},
              {"method", "monodromy"},
              {"integrator", r.integrator},
              {"tolerance", args.options.integrator.rel_tol},
              {"multiplier_method", r.multiplier_method},
              {"segments", r.segments},
              {"branch_rule", "energy centroid of the periodic mode shape on harmonic 0"},
              {"exponents", exps},
              {"multipliers", mults},
              {"modes", modes},
              {"max_real_exponent", JsonNumber(r.max_real_exponent)},
              {"max_log_abs_multiplier", JsonNumber(r.max_log_abs_multiplier)},
              {"stable", r.stable},
              {"error_estimate", JsonNumber(r.error_estimate)},
              {"liouville_residual", JsonNumber(r.liouville_residual)},
              {"mode_condition", JsonNumber(r.mode_condition)},
              {"rhs_evals", r.rhs_evals},
              {"elapsed_s", r.elapsed_s},
              {"ok", r.ok},
              {"diagnostics", r.diagnostics}};
    std::cout << j.dump(2) << "\n";
    return r.ok ? 0 : 1;
  }

  std::cout << "Floquet analysis of " << l.scene.name;
  if (!l.parameters.empty()) std::cout << " (" << ParameterList(l.parameters) << ")";
  std::cout << "\n  " << r.states << " states, period T = " << Num(T, 10) << " s (Ωp = "
            << Num(2 * kPi / T, 8) << " rad/s)\n  monodromy by " << r.integrator << " (rel tol "
            << args.options.integrator.rel_tol << ") over K = " << r.segments
            << " segments; multipliers by " << r.multiplier_method << "\n";
  if (!r.ok) {
    std::cout << "\nFAILED:\n";
    for (const auto& d : r.diagnostics) std::cout << "  - " << d << "\n";
    return 1;
  }
  std::cout << "\n  mode      Re λ [1/s]    Im λ [rad/s]     freq [Hz]   damping ζ     log|ρ|    arg ρ [rad]  branch\n";
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const FloquetMode& m = r.modes[k];
    std::cout << "  " << std::setw(4) << k + 1 << Num(m.exponent.real(), 7, 15)
              << Num(m.exponent.imag(), 7, 16) << Num(m.frequency_hz, 6, 14)
              << Num(m.damping_ratio, 4, 12) << Num(m.log_multiplier.real(), 6, 11)
              << Num(m.log_multiplier.imag(), 6, 15) << std::setw(8) << m.branch << "\n";
  }
  std::cout << "\n  max Re λ = " << Num(r.max_real_exponent, 8) << " 1/s  →  "
            << (r.stable ? "STABLE" : "UNSTABLE") << "   (max log|ρ| = "
            << Num(r.max_log_abs_multiplier, 8) << ")\n"
            << "  error estimate " << Num(r.error_estimate, 2)
            << " 1/s on every exponent (difference to the run at the requested tolerance on\n"
            << "  half as many segments; the numbers shown come from the refined, 100× tighter run)\n"
            << "  Liouville residual " << Num(r.liouville_residual, 2) << ", cond(Ξ(0)) "
            << Num(r.mode_condition, 3) << ", " << r.rhs_evals << " evaluations of A(t), "
            << Num(r.elapsed_s * 1e3, 3) << " ms\n"
            << "  branch: Im λ chosen so each periodic mode shape's Fourier energy is centred on "
               "harmonic 0\n";
  if (!r.diagnostics.empty()) {
    std::cout << "  diagnostics:\n";
    for (const auto& d : r.diagnostics) std::cout << "    - " << d << "\n";
  }
  return 0;
}

}  // namespace

Command AddFloquetCommand(CLI::App& app) {
  static FloquetArgs args;
  auto* cmd = app.add_subcommand(
      "floquet", "Floquet exponents, multipliers and periodic modes via the monodromy matrix");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--integrator", args.integrator,
                  "dopri5 | rkf78 | cvode | cvode-adams | magnus4 | magnus6 | expm")
      ->capture_default_str();
  cmd->add_option("--tol", args.options.integrator.rel_tol, "relative tolerance")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--steps", args.options.integrator.steps_per_period,
                  "fixed-step methods: steps per period (0 = automatic)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--segments", args.segments, "number of segments K, or auto")->capture_default_str();
  cmd->add_option("--multipliers", args.multipliers,
                  "schur (periodic Schur of the segment factors) | single-shot (eig of the formed Φ)")
      ->capture_default_str();
  cmd->add_option("--mode-samples", args.options.mode_samples,
                  "samples of the mode shapes per period (power of two; 0 = automatic)")
      ->capture_default_str();
  cmd->add_option("--threads", args.options.threads, "OpenMP threads (0 = all cores)")
      ->capture_default_str();
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  cmd->add_option("--modes-csv", args.modes_csv, "write the periodic mode shapes ξ_k(t) to CSV");
  cmd->add_option("--plot", args.plot, "draw exponents and mode-shape spectra (FILE.svg or FILE.png)");
  return {cmd, [] { return RunFloquet(args); }};
}

}  // namespace ltp::cli
