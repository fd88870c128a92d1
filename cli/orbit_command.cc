// `ltp orbit`: the response orbit of a rotor, order by order, in the plane of two outputs under
// a sinusoidal input (an unbalance, or any complex weights on the inputs), at one or a list of
// excitation frequencies — every value from one harmonic transfer function (one Floquet
// analysis), checked by its second route (ltp/htf/response_orbit.h).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "command.h"
#include "format.h"
#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/core/text.h"
#include "ltp/core/whirl.h"
#include "ltp/htf/frequency_range.h"
#include "ltp/htf/harmonic_transfer_function.h"
#include "ltp/htf/response_orbit.h"
#include "plot.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
using cd = std::complex<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;

struct OrbitArgs {
  SceneArgs scene;
  std::string x = "0", y = "1";
  std::string input, unbalance;
  std::string freq;
  std::string orders = std::to_string(OrbitSweepOptions{}.min_order) + ":" +
                       std::to_string(OrbitSweepOptions{}.max_order);
  std::string route = "auto";
  std::string csv, plot;
  bool json = false;
};

// What the command line chose: the plane, the input and its description.
struct OrbitSetup {
  int x = 0, y = 1;
  std::string x_name, y_name;
  Eigen::VectorXcd input;
  std::string input_text;  ///< "fx = 1, fy = -1j"
  bool unbalance = false;
  std::vector<double> frequencies_hz;
  OrbitSweepOptions options;
};

// A real number at the start of `s` (strtod), advancing `s`; false when there is none.
bool TakeNumber(const char*& s, double* x) {
  char* end = nullptr;
  *x = std::strtod(s, &end);
  if (end == s) return false;
  s = end;
  return true;
}

// "1", "-1j", "-j", "0.5+0.2j", "1e-3-2e-3j", or polar "MAG@DEG" (degrees).
cd ParseWeight(const std::string& text, const std::string& option) {
  const std::string bad =
      option + ": '" + text + "' is not a complex number (1, -1j, 0.5+0.2j or 2@90)";
  const char* s = text.c_str();
  double a = 0, b = 0;
  if (const size_t at = text.find('@'); at != std::string::npos) {
    const std::string mag = text.substr(0, at), deg = text.substr(at + 1);
    const char *m = mag.c_str(), *d = deg.c_str();
    if (!TakeNumber(m, &a) || *m || !TakeNumber(d, &b) || *d) throw InputError(bad);
    if (!std::isfinite(a) || !std::isfinite(b)) throw InputError(bad);
    return std::polar(a, b * std::numbers::pi / 180);
  }
  // An imaginary part alone: "j", "-j", "+j", "2j"; else a real part and an optional "±Bj".
  const auto bare_j = [](const char* p, double* sign) {
    const char* q = p;
    *sign = 1;
    if (*q == '+' || *q == '-') *sign = *q++ == '-' ? -1 : 1;
    return *q == 'j' && q[1] == '\0';
  };
  double sign = 1;
  if (bare_j(s, &sign)) return {0, sign};
  if (!TakeNumber(s, &a)) throw InputError(bad);
  if (*s == 'j' && s[1] == '\0') {
    b = a;
    a = 0;
  } else if (*s && bare_j(s, &sign)) {
    b = sign;
  } else if (*s) {
    if ((*s != '+' && *s != '-') || !TakeNumber(s, &b) || *s != 'j' || s[1]) throw InputError(bad);
  }
  if (!std::isfinite(a) || !std::isfinite(b)) throw InputError(bad);
  return {a, b};
}

std::string WeightText(cd w) {
  if (w.imag() == 0) return Num(w.real(), 6);
  if (w.real() == 0) return Num(w.imag(), 6) + "j";
  return Num(w.real(), 6) + (w.imag() < 0 ? "" : "+") + Num(w.imag(), 6) + "j";
}

std::string InputName(const PeriodicSystem& sys, int i) {
  const auto& names = sys.labels().inputs;
  return i < static_cast<int>(names.size()) ? names[static_cast<size_t>(i)] : std::to_string(i);
}

// --input NAME=W,... (weights; inputs not named are 0).
Eigen::VectorXcd ParseInputWeights(const std::string& text, const PeriodicSystem& sys) {
  Eigen::VectorXcd u = Eigen::VectorXcd::Zero(sys.inputs());
  std::vector<bool> given(static_cast<size_t>(sys.inputs()), false);
  for (const std::string& item : SplitAt(text, ',')) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos)
      throw InputError("--input: expected NAME=WEIGHT items separated by commas, got '" + item +
                       "'");
    const int i =
        ResolveChannel(item.substr(0, eq), sys.labels().inputs, sys.inputs(), "--input", "input");
    if (given[static_cast<size_t>(i)])
      throw InputError("--input: input '" + InputName(sys, i) + "' is given twice");
    given[static_cast<size_t>(i)] = true;
    u(i) = ParseWeight(item.substr(eq + 1), "--input " + item.substr(0, eq));
  }
  if (u.cwiseAbs().maxCoeff() == 0) throw InputError("--input: every weight is zero");
  return u;
}

// --unbalance FX,FY: UnbalanceInput on those two inputs.
Eigen::VectorXcd UnbalanceFrom(const std::string& text, const PeriodicSystem& sys,
                               const std::string& scene) {
  if (sys.inputs() < 2)
    throw InputError("--unbalance needs two force inputs; scene '" + scene + "' has " +
                     std::to_string(sys.inputs()) + " (use --input NAME=WEIGHT)");
  const std::vector<std::string> pair = SplitAt(text, ',');
  if (pair.size() != 2 || pair[0].empty() || pair[1].empty())
    throw InputError("--unbalance: expected FX,FY (two inputs), got '" + text + "'");
  const std::string& fx = pair[0];
  const int ix = ResolveChannel(fx, sys.labels().inputs, sys.inputs(), "--unbalance", "input");
  const int iy = ResolveChannel(pair[1], sys.labels().inputs, sys.inputs(), "--unbalance", "input");
  if (ix == iy) throw InputError("--unbalance: FX and FY name the same input '" + fx + "'");
  return UnbalanceInput(sys.inputs(), ix, iy, RotorSpin(sys));
}

std::string OutputName(const PeriodicSystem& sys, int i) {
  const auto& names = sys.labels().outputs;
  return i < static_cast<int>(names.size()) ? names[static_cast<size_t>(i)] : "";
}

OrbitSetup SetupFrom(const OrbitArgs& args, const LoadedScene& l) {
  const PeriodicSystem& sys = l.system;
  OrbitSetup s;
  if (sys.outputs() < 2)
    throw InputError("scene '" + l.scene.name + "' has " + std::to_string(sys.outputs()) +
                     " output(s); an orbit needs two (--x, --y)");
  s.x = ResolveChannel(args.x, sys.labels().outputs, sys.outputs(), "--x", "output");
  s.y = ResolveChannel(args.y, sys.labels().outputs, sys.outputs(), "--y", "output");
  if (s.x == s.y) throw InputError("--x and --y name the same output '" + args.x + "'");
  s.x_name = OutputName(sys, s.x);
  s.y_name = OutputName(sys, s.y);
  if (args.input.empty() == args.unbalance.empty())
    throw InputError("give either --unbalance FX,FY or --input NAME=WEIGHT,... (one of them)");
  s.unbalance = !args.unbalance.empty();
  s.input = s.unbalance ? UnbalanceFrom(args.unbalance, sys, l.scene.name)
                        : ParseInputWeights(args.input, sys);
  for (int i = 0; i < sys.inputs(); ++i)
    if (s.input(i) != cd(0))
      s.input_text +=
          (s.input_text.empty() ? "" : ", ") + InputName(sys, i) + " = " + WeightText(s.input(i));
  s.frequencies_hz = ParseFrequencyList(args.freq, "--freq");
  std::tie(s.options.min_order, s.options.max_order) = ParseOrderRange(args.orders, "--orders");
  if (args.route != "auto") {
    const auto route = ParseOperatorRoute(args.route);
    if (!route) throw InputError("--route must be auto, modal or hill, got '" + args.route + "'");
    s.options.route = *route;
  }
  return s;
}

double TiltDeg(const OrbitSweep& r, size_t i, size_t k) {
  const Orbit& o = r.orbits[i][k].orbit;
  return HasTilt(o, r.uncertainty[i][k]) ? o.tilt * 180 / std::numbers::pi
                                         : std::numeric_limits<double>::quiet_NaN();
}

void WriteCsv(const OrbitSweep& r, const std::string& file) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "f_exc_hz,z,f_resp_hz,x_re,x_im,y_re,y_im,forward,backward,semi_major,semi_minor,"
         "tilt_deg,whirl,error_estimate\n";
  for (size_t i = 0; i < r.orbits.size(); ++i)
    for (size_t k = 0; k < r.orbits[i].size(); ++k) {
      const ResponseOrbit& o = r.orbits[i][k];
      std::string row;
      for (double v : {r.omegas[i] / kTwoPi, static_cast<double>(o.order), o.frequency / kTwoPi,
                       o.x.real(), o.x.imag(), o.y.real(), o.y.imag(), o.orbit.forward,
                       o.orbit.backward, o.orbit.semi_major, o.orbit.semi_minor}) {
        AppendCsvNumber(row, v);
        row += ",";
      }
      const double tilt = TiltDeg(r, i, k);
      row += (std::isnan(tilt) ? "" : CsvNumber(tilt)) + "," +
             std::string(ToString(r.sense[i][k])) + "," +
             (r.error_estimate.empty() ? "" : CsvNumber(r.error_estimate[i][k]));
      csv << row << "\n";
    }
}

json OrbitsJson(const OrbitSweep& r) {
  json freqs = json::array();
  for (size_t i = 0; i < r.orbits.size(); ++i) {
    json orders = json::array();
    for (size_t k = 0; k < r.orbits[i].size(); ++k) {
      const ResponseOrbit& o = r.orbits[i][k];
      const double tilt = TiltDeg(r, i, k);
      orders.push_back(
          {{"z", o.order},
           {"f_resp_hz", o.frequency / kTwoPi},
           {"x", {{"re", JsonNumber(o.x.real())}, {"im", JsonNumber(o.x.imag())}}},
           {"y", {{"re", JsonNumber(o.y.real())}, {"im", JsonNumber(o.y.imag())}}},
           {"forward", JsonNumber(o.orbit.forward)},
           {"backward", JsonNumber(o.orbit.backward)},
           {"semi_major", JsonNumber(o.orbit.semi_major)},
           {"semi_minor", JsonNumber(o.orbit.semi_minor)},
           {"tilt_deg", std::isnan(tilt) ? json(nullptr) : json(tilt)},
           {"whirl", std::string(ToString(r.sense[i][k]))},
           {"error_estimate",
            r.error_estimate.empty() ? json(nullptr) : JsonNumber(r.error_estimate[i][k])}});
    }
    freqs.push_back({{"f_exc_hz", r.omegas[i] / kTwoPi}, {"orders", orders}});
  }
  return freqs;
}

json OrbitJson(const OrbitSweep& r, const HarmonicTransferFunction& htf, const LoadedScene& l,
               const OrbitSetup& s) {
  json input = json::array();
  for (int i = 0; i < s.input.size(); ++i)
    if (s.input(i) != cd(0))
      input.push_back({{"input", i},
                       {"name", InputName(l.system, i)},
                       {"re", s.input(i).real()},
                       {"im", s.input(i).imag()}});
  const FloquetResult& f = htf.floquet();
  return {{"scene", l.scene.name},
          {"parameters", ParametersJson(l.parameters)},
          {"x", s.x},
          {"x_name", s.x_name},
          {"y", s.y},
          {"y_name", s.y_name},
          {"input", input},
          {"unbalance", s.unbalance},
          {"spin", r.spin},
          {"period", l.system.period()},
          {"fp_hz", 1 / l.system.period()},
          {"orders", {r.min_order, r.max_order}},
          {"route", std::string(ToString(r.route))},
          {"check_route", r.check_route ? json(std::string(ToString(*r.check_route))) : json()},
          {"route_choice", r.route_choice},
          {"route_reason", std::string(CodeName(r.route_reason))},
          {"hill_harmonics", htf.hill_harmonics()},
          {"max_disagreement", JsonNumber(r.max_disagreement)},
          {"max_relative_disagreement", JsonNumber(r.max_relative_disagreement)},
          {"max_semi_major", JsonNumber(r.max_semi_major)},
          {"max_real_exponent", JsonNumber(f.max_real_exponent)},
          {"verdict", ToString(f.verdict)},
          {"frequencies", OrbitsJson(r)},
          {"ok", r.ok},
          {"failure", r.failure},
          {"diagnostics", Texts(r.diagnostics)},
          {"htf_diagnostics", Texts(htf.diagnostics())}};
}

void PrintHeader(const OrbitSweep& r, const HarmonicTransferFunction& htf, const LoadedScene& l,
                 const OrbitSetup& s) {
  const PeriodicSystem& sys = l.system;
  const auto named = [](int i, const std::string& name) {
    return "output " + std::to_string(i) + (name.empty() ? "" : " (" + name + ")");
  };
  std::cout << "Response orbits of " << l.scene.name;
  if (!l.parameters.empty()) std::cout << " (" << ParameterList(l.parameters) << ")";
  std::cout << "\n  plane: x = " << named(s.x, s.x_name) << ", y = " << named(s.y, s.y_name)
            << "; the rotor turns from " << (r.spin > 0 ? "x towards y" : "y towards x")
            << " (FW: with the rotor, BW: against it)\n  input: " << s.input_text
            << (s.unbalance ? "  (unit unbalance: a force of magnitude 1 turning with the rotor "
                              "at the excitation frequency)"
                            : "  (u = Re(weights · e^{jωt}))")
            << "\n  " << sys.states() << " states, T = " << Num(sys.period(), 10)
            << " s, fp = " << Num(1 / sys.period(), 8) << " Hz; " << s.frequencies_hz.size()
            << (s.frequencies_hz.size() == 1 ? " excitation frequency" : " excitation frequencies")
            << ", orders z = " << r.min_order << " … " << r.max_order
            << "\n  one set-up for every value: Floquet max Re λ = "
            << Num(htf.floquet().max_real_exponent, 6) << " 1/s ("
            << ToString(htf.floquet().verdict) << ")";
  if (htf.modal())
    std::cout << ", modal cond Ξ = " << Num(htf.modal()->condition, 3)
              << (htf.modal()->reliable ? "" : " (UNRELIABLE)");
  std::cout << ", Hill N = " << htf.hill_harmonics() << "\n  route " << ToString(r.route) << " ("
            << r.route_choice << ")";
  if (r.check_route)
    std::cout << ", checked by " << ToString(*r.check_route) << " at every frequency: max |Δ| "
              << Num(r.max_disagreement, 3) << " (" << Num(r.max_relative_disagreement, 3)
              << " of the largest semi-major axis " << Num(r.max_semi_major, 4) << ")";
  std::cout << "\n";
}

void PrintTable(const OrbitSweep& r, size_t i) {
  std::cout << "\n  f = " << Num(r.omegas[i] / kTwoPi, 8) << " Hz\n"
            << "      z   f_resp [Hz]       forward      backward    semi-major    semi-minor"
               "   tilt [°]  whirl    error est.\n";
  for (size_t k = 0; k < r.orbits[i].size(); ++k) {
    const ResponseOrbit& o = r.orbits[i][k];
    const double tilt = TiltDeg(r, i, k);
    std::cout << std::setw(7) << o.order << Num(o.frequency / kTwoPi, 6, 14)
              << Num(o.orbit.forward, 6, 14) << Num(o.orbit.backward, 6, 14)
              << Num(o.orbit.semi_major, 6, 14) << Num(o.orbit.semi_minor, 6, 14)
              << (std::isnan(tilt) ? std::string(11, ' ') + "-" : Num(tilt, 5, 12)) << std::setw(7)
              << ToString(r.sense[i][k])
              << (r.error_estimate.empty() ? std::string(14, ' ') + "-"
                                           : Num(r.error_estimate[i][k], 2, 14))
              << "\n";
  }
}

// Per order: the largest forward and backward radius over the frequencies, and where.
void PrintPeaks(const OrbitSweep& r, bool written) {
  std::cout << "\n      z   max forward   at f [Hz]  max backward   at f [Hz]\n";
  for (size_t k = 0; k < r.orbits.front().size(); ++k) {
    size_t fi = 0, bi = 0;
    for (size_t i = 0; i < r.orbits.size(); ++i) {
      if (r.orbits[i][k].orbit.forward > r.orbits[fi][k].orbit.forward) fi = i;
      if (r.orbits[i][k].orbit.backward > r.orbits[bi][k].orbit.backward) bi = i;
    }
    std::cout << std::setw(7) << r.orbits[0][k].order << Num(r.orbits[fi][k].orbit.forward, 6, 14)
              << Num(r.omegas[fi] / kTwoPi, 6, 12) << Num(r.orbits[bi][k].orbit.backward, 6, 14)
              << Num(r.omegas[bi] / kTwoPi, 6, 12) << "\n";
  }
  if (!written)
    std::cout << "\n  (" << r.orbits.size()
              << " frequencies: every value with --csv FILE or --json; a table per frequency "
                 "for 12 or fewer)\n";
}

void PrintOrbits(const OrbitSweep& r, const HarmonicTransferFunction& htf, const LoadedScene& l,
                 const OrbitSetup& s, bool written) {
  PrintHeader(r, htf, l, s);
  if (r.orbits.size() <= 12)
    for (size_t i = 0; i < r.orbits.size(); ++i) PrintTable(r, i);
  else
    PrintPeaks(r, written);
  std::vector<std::string> notes = Texts(r.diagnostics);
  if (!htf.ok())
    for (const Diagnostic& d : htf.diagnostics()) notes.push_back(d.text);
  if (!notes.empty()) {
    std::cout << "\n  notes:\n";
    for (const std::string& d : notes) std::cout << "    - " << d << "\n";
  }
}

// One frequency: the ellipse of each order in the (x, y) plane, a dot where it is at t = 0 and
// an arrow the way it turns.
void PlotEllipses(const OrbitSweep& r, const std::string& title, const OrbitSetup& s,
                  const std::string& file) {
  std::ostringstream p;
  p << GnuplotTerminal(file, 760, 700) << "set output '" << file << "'\n"
    << "set title \"" << title << "  at f = " << Num(r.omegas[0] / kTwoPi, 6)
    << " Hz\"\nset xlabel \"x: "
    << GnuplotEscape(s.x_name.empty() ? "output " + std::to_string(s.x) : s.x_name)
    << "\"\nset ylabel \"y: "
    << GnuplotEscape(s.y_name.empty() ? "output " + std::to_string(s.y) : s.y_name)
    << "\"\nset size ratio -1\nset grid\nset key outside below\n";
  std::vector<size_t> shown;
  for (size_t k = 0; k < r.orbits[0].size(); ++k)
    if (r.sense[0][k] != OrbitSense::kStill) shown.push_back(k);
  for (size_t k : shown) {
    const ResponseOrbit& o = r.orbits[0][k];
    p << "$E" << k << " << EOD\n";
    for (int q = 0; q <= 180; ++q) {
      const cd e = std::polar(1.0, kTwoPi * q / 180);
      p << (o.x * e).real() << " " << (o.y * e).real() << "\n";
    }
    // The arrow: from t = 0 a sixteenth of a turn along the orbit (the way time runs).
    const cd e = std::polar(1.0, (o.frequency >= 0 ? 1 : -1) * kTwoPi / 16);
    p << "EOD\n$A" << k << " << EOD\n"
      << o.x.real() << " " << o.y.real() << " " << (o.x * e).real() - o.x.real() << " "
      << (o.y * e).real() - o.y.real() << "\nEOD\n";
  }
  if (shown.empty()) {
    p << "plot NaN title 'no order moves'\n";
  } else {
    p << "plot ";
    for (size_t q = 0; q < shown.size(); ++q) {
      const size_t k = shown[q];
      const ResponseOrbit& o = r.orbits[0][k];
      p << (q ? ", " : "") << "$E" << k << " using 1:2 with lines lw 2 lc " << q + 1
        << " title 'z = " << o.order << " (" << Num(o.frequency / kTwoPi, 4) << " Hz, "
        << ToString(r.sense[0][k]) << ")', $A" << k
        << " using 1:2:3:4 with vectors head filled lw 2 lc " << q + 1 << " notitle, $A" << k
        << " using 1:2 with points pt 7 ps 1 lc " << q + 1 << " notitle";
    }
    p << "\n";
  }
  RunGnuplot(file, p.str());
}

// Several frequencies: forward (solid) and backward (dashed) radius of each order against the
// excitation frequency; values judged still are left out.
void PlotRadii(const OrbitSweep& r, const std::string& title, const std::string& file) {
  std::ostringstream p;
  p << GnuplotTerminal(file, 1000, 560) << "set output '" << file << "'\n"
    << "set title \"" << title << ": orbit radii per order\"\n"
    << "set xlabel 'excitation frequency f  [Hz]  (order z answers at f + z f_p)'\n"
    << "set ylabel 'radius'\nset logscale y\nset format y '10^{%L}'\nset grid\n"
    << "set key outside right\n";
  std::vector<size_t> shown;
  for (size_t k = 0; k < r.orbits[0].size(); ++k) {
    bool moves = false;
    for (size_t i = 0; i < r.orbits.size(); ++i) moves |= r.sense[i][k] != OrbitSense::kStill;
    if (moves) shown.push_back(k);
  }
  const auto value = [](double radius, double uncertainty) {
    return radius > uncertainty ? Num(radius, 10) : std::string("NaN");
  };
  for (size_t k : shown) {
    p << "$R" << k << " << EOD\n";
    for (size_t i = 0; i < r.orbits.size(); ++i) {
      const Orbit& o = r.orbits[i][k].orbit;
      p << Num(r.omegas[i] / kTwoPi, 12) << " " << value(o.forward, r.uncertainty[i][k]) << " "
        << value(o.backward, r.uncertainty[i][k]) << "\n";
    }
    p << "EOD\n";
  }
  if (shown.empty()) {
    p << "plot NaN title 'no order moves'\n";
  } else {
    // A circle that stays below its uncertainty at every frequency gets no line (nor a key).
    const auto above = [&](size_t k, bool forward) {
      for (size_t f = 0; f < r.orbits.size(); ++f) {
        const Orbit& o = r.orbits[f][k].orbit;
        if ((forward ? o.forward : o.backward) > r.uncertainty[f][k]) return true;
      }
      return false;
    };
    p << "plot ";
    const char* separator = "";
    for (size_t q = 0; q < shown.size(); ++q) {
      const size_t k = shown[q];
      const int z = r.orbits[0][k].order;
      for (const bool forward : {true, false}) {
        if (!above(k, forward)) continue;
        p << separator << "$R" << k << " using 1:" << (forward ? 2 : 3) << " with lines lw 2"
          << (forward ? "" : " dt 2") << " lc " << q + 1 << " title 'z = " << z
          << (forward ? " forward'" : " backward'");
        separator = ", ";
      }
    }
    p << "\n";
  }
  RunGnuplot(file, p.str());
}

int RunOrbit(const OrbitArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // reject a bad extension up front
  LoadedScene l = LoadSceneArgs(args.scene);
  const OrbitSetup s = SetupFrom(args, l);
  HtfOperatorOptions ho;  // the Hill route's truncation fits the orders asked, at least ±4
  ho.probe_orders =
      std::max({ho.probe_orders, std::abs(s.options.min_order), std::abs(s.options.max_order)});
  const HarmonicTransferFunction htf(l.system, ho);
  std::vector<double> omegas;
  for (double f : s.frequencies_hz) omegas.push_back(kTwoPi * f);
  const OrbitSweep r = ResponseOrbitSweep(htf, omegas, s.input, s.x, s.y, s.options);
  if (!args.csv.empty()) WriteCsv(r, args.csv);
  if (!args.plot.empty()) {
    const std::string title = GnuplotEscape("Response orbits of " + l.scene.name);
    if (r.orbits.size() == 1)
      PlotEllipses(r, title, s, args.plot);
    else
      PlotRadii(r, title, args.plot);
  }
  if (args.json)
    std::cout << OrbitJson(r, htf, l, s).dump(2) << "\n";
  else
    PrintOrbits(r, htf, l, s, !args.csv.empty());
  if (!r.ok) SetFailureFrom("response orbits", r.failure);
  return r.ok ? 0 : 1;
}

}  // namespace

Command AddOrbitCommand(CLI::App& app) {
  static OrbitArgs args;
  args = OrbitArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "orbit",
      "Response orbits of a rotor per harmonic (forward/backward circles, ellipse) under an "
      "unbalance or any sinusoidal input, from one harmonic transfer function");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--x", args.x, "output along the orbit's x axis: index from 0 or name")
      ->capture_default_str();
  cmd->add_option("--y", args.y, "output along the orbit's y axis: index from 0 or name")
      ->capture_default_str();
  cmd->add_option("--unbalance", args.unbalance,
                  "FX,FY: a unit unbalance on these two force inputs, weights (1, -j) (fx = cos "
                  "ωt, fy = sin ωt) for a rotor turning from x towards y, (1, +j) the other way");
  cmd->add_option("--input", args.input,
                  "NAME=WEIGHT,...: complex weights U of the input Re(U e^{jωt}) (1, -1j, "
                  "0.5+0.2j or MAG@DEG; inputs not named are 0)");
  cmd->add_option("--freq", args.freq,
                  "excitation frequencies in Hz: F, F1,F2,... or F0:F1:DF (items may mix)")
      ->required();
  cmd->add_option("--orders", args.orders, "orders z, ZMIN:ZMAX")->capture_default_str();
  cmd->add_option("--route", args.route,
                  "auto | modal | hill (the reported values; the other route checks them; auto: "
                  "modal unless it reports itself unreliable)")
      ->capture_default_str();
  cmd->add_option("--csv", args.csv, "write every order at every frequency to CSV");
  cmd->add_option("--plot", args.plot,
                  "draw the ellipses (one frequency) or the radii against frequency (several): "
                  "FILE.svg or .png");
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  return {cmd, [] { return RunOrbit(args); }};
}

}  // namespace ltp::cli
