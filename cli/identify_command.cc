// `ltp identify DATA.csv`: partial FRFs H_z from step-sine time data (paper eq. 47) or from
// broadband records (least squares across records per response line, §4.2), each with a 95 %
// bound; `--compare SCENE` sets the model's values beside them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>

#include "command.h"
#include "daq_csv.h"
#include "format.h"
#include "frf_args.h"
#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/htf/frequency_range.h"
#include "ltp/htf/identify.h"
#include "ltp/htf/pfrf.h"
#include "ltp/htf/rotor_angle.h"
#include "ltp/models/scene_input.h"
#include "plot.h"
#include "time_data_csv.h"
#include "uff58.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
using cd = std::complex<double>;

struct IdentifyArgs {
  std::vector<std::string> files;
  std::string method = "auto";
  // Empty: not given (a given 0 or nan is an error, not "absent").
  std::string period, rotor_speed, sample_rate;
  std::string input = "0", orders = "-2:2", plot_orders;
  std::vector<std::string> outputs{"0"};
  std::string compare, csv, plot, convergence, uff;
  bool binary = false;              ///< --uff as 58b
  std::vector<std::string> set;     ///< parameters of the --compare scene
  std::string tacho, angle;         ///< aux channels giving the rotor's phase
  std::vector<std::string> delays;  ///< CHANNEL=SECONDS
  int pulses_per_period = 1;
  double tacho_angle_deg = 0;
  bool json = false;
};

// A number option that must be finite and > 0 when given; 0 when not.
double PositiveOption(const std::string& text, const std::string& name) {
  if (text.empty()) return 0;
  const std::optional<double> x = NumberIn(text);
  if (!x || !(*x > 0) || !std::isfinite(*x))
    throw InputError(name + " must be a finite number > 0, got '" + text + "'");
  return *x;
}

// ltp's CSV (one file), or DAQ CSV files (one record each) and UFF 58 files (a record per
// repetition of its channels), the channels named by --input and --output; every channel also
// an aux: channel for --tacho / --angle.
TimeData ReadTimeData(const IdentifyArgs& args, double period, bool require_period,
                      bool* ltp_format) {
  *ltp_format = args.files.size() == 1 && IsLtpTimeData(args.files.front());
  if (*ltp_format) {
    if (!args.sample_rate.empty())
      throw InputError("--sample-rate: ltp's time-data CSV has its own time column");
    return ReadTimeDataCsv(args.files.front(), period, require_period);
  }
  std::vector<ChannelTable> tables;
  for (const std::string& f : args.files) {
    if (IsLtpTimeData(f))
      throw InputError(f + ": ltp's time-data CSV is read alone, not with DAQ files");
    if (IsUffFile(f)) {
      const std::vector<ChannelTable> records = ReadUffTimeRecords(f);
      tables.insert(tables.end(), records.begin(), records.end());
    } else {
      tables.push_back(ReadDaqCsv(f, PositiveOption(args.sample_rate, "--sample-rate")));
    }
  }
  TimeData data = TimeDataFromTables(tables, args.input, args.outputs, period);
  if (period <= 0 && require_period)
    throw InputError(
        "DAQ and UFF files carry no period: give --period T, --rotor-speed W or --tacho");
  return data;
}

// The records' phase from --tacho or --angle (none: the model's 2πt/T); the speeds measured.
std::optional<MeasuredSpeeds> MeasureAngles(const IdentifyArgs& args, TimeData& data) {
  if (args.tacho.empty() && args.angle.empty()) return std::nullopt;
  if (!args.tacho.empty() && !args.angle.empty())
    throw InputError("--tacho and --angle: give one source of the rotor's phase");
  AngleChannel source;
  source.kind = args.tacho.empty() ? AngleChannel::Kind::kEncoder : AngleChannel::Kind::kTacho;
  const std::string& spec = args.tacho.empty() ? args.angle : args.tacho;
  source.channel =
      ResolveChannel(spec, data.auxiliary_names, static_cast<int>(data.auxiliary_names.size()),
                     args.tacho.empty() ? "--angle" : "--tacho", "aux: channel");
  source.tacho.pulses_per_period = args.pulses_per_period;
  source.tacho.pulse_angle = args.tacho_angle_deg * std::numbers::pi / 180;
  return SetMeasuredAngles(data, source);
}

// |H_z| (log) and its phase per order against the excitation frequency: the estimates their
// 95 % bound resolves (bound below |H_z|) with the bound as error bar (in phase: asin(bound /
// |H_z|)), the others as grey dots on the magnitude panel (indistinguishable from 0 at this
// noise), the model's values as lines (--compare; orders whose model is zero to round-off are
// left out). Phase is where a rig's biases show (a speed offset turns H_±1, not its size).
void PlotIdentified(const std::string& file, const IdentifyResult& r,
                    const std::vector<std::vector<cd>>& model, const std::string& title,
                    const std::string& method, std::pair<int, int> shown) {
  const int Z = r.max_order - r.min_order + 1;
  const auto hidden = [&](int z) {
    return z + r.min_order < shown.first || z + r.min_order > shown.second;
  };
  const auto degrees = [](cd h) { return PhaseDeg(h.real(), h.imag()); };
  std::ostringstream g;
  g << GnuplotTerminal(file, 1000, 900) << "set output '" << file << "'\n";
  double model_max = 0;
  for (const auto& row : model)
    for (const cd& v : row) model_max = std::max(model_max, std::abs(v));
  std::vector<bool> drawn_model(Z, false);
  g << "$U << EOD\n";
  for (const auto& f : r.frequencies)
    for (int z = 0; z < Z; ++z) {
      const double h = std::abs(f.h[static_cast<size_t>(z)]);
      if (hidden(z)) continue;
      if (f.separable && h > 0 && std::isfinite(h) && !(f.bound[static_cast<size_t>(z)] < h))
        g << f.excitation_hz << " " << h << "\n";
    }
  g << "EOD\n";
  for (int z = 0; z < Z; ++z) {
    g << "$E" << z << " << EOD\n";  // f, |H|, bound, phase, phase bound
    for (const auto& f : r.frequencies) {
      const cd h = f.h[static_cast<size_t>(z)];
      const double bound = f.bound[static_cast<size_t>(z)];
      if (std::isfinite(std::abs(h)) && bound < std::abs(h))
        g << f.excitation_hz << " " << std::abs(h) << " " << bound << " " << degrees(h) << " "
          << std::asin(bound / std::abs(h)) * 180 / std::numbers::pi << "\n";
    }
    g << "EOD\n";
    double order_max = 0;
    for (const auto& row : model)
      order_max = std::max(order_max, std::abs(row[static_cast<size_t>(z)]));
    drawn_model[z] = !model.empty() && order_max > 1e-9 * model_max;
    if (drawn_model[z]) {
      g << "$M" << z << " << EOD\n";
      for (size_t f = 0; f < r.frequencies.size(); ++f)
        g << r.frequencies[f].excitation_hz << " " << std::abs(model[f][static_cast<size_t>(z)])
          << "\n";
      g << "EOD\n$P" << z << " << EOD\n";
      double previous = 0;
      for (size_t f = 0; f < r.frequencies.size(); ++f) {
        const double phase = degrees(model[f][static_cast<size_t>(z)]);
        if (f > 0 && std::abs(phase - previous) > 180) g << "\n";  // wrapped: a new segment
        previous = phase;
        g << r.frequencies[f].excitation_hz << " " << phase << "\n";
      }
      g << "EOD\n";
    }
  }
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                          "#17becf", "#8c564b", "#e377c2", "#7f7f7f"};
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const auto& f : r.frequencies) {
    low = std::min(low, f.excitation_hz);
    high = std::max(high, f.excitation_hz);
  }
  const double pad = high > low ? 0.02 * (high - low) : 0.05 * std::max(high, 1e-9);
  g << "set multiplot layout 2,1 title \"" << GnuplotEscape(title) << "\" font ',12'\n"
    << "set xrange [" << low - pad << ":" << high + pad << "]\n"
    << "set grid\nset key outside right top\nset lmargin 12\nset rmargin 42\n"
    << "set ylabel '|H_z|'\nset logscale y\nset format y '10^{%L}'\nset format x ''\n"
    << "set bmargin 1\n";
  g << "plot $U using 1:2 with points pt 7 ps 0.25 lc rgb '#c0c0c0' title 'within the 95 % bound "
       "of 0'";
  for (int z = 0; z < Z; ++z) {
    if (hidden(z)) continue;
    const std::string color = colors[z % 9];
    g << ", \\\n     $E" << z << " using 1:2:3 with yerrorbars pt 7 ps 0.5 lc rgb '" << color
      << "' title 'z = " << z + r.min_order << " (" << method << ", 95 % bound)'";
    if (drawn_model[z])
      g << ", $M" << z << " using 1:2 with lines lw 1.2 lc rgb '" << color
        << "' title 'z = " << z + r.min_order << " model'";
  }
  g << "\nunset logscale y\nset format y '%g'\nset format x '%g'\nset tmargin 1\nset bmargin\n"
    << "set ylabel 'phase of H_z  [°]'\nset xlabel 'excitation frequency  [Hz]'\n"
    << "set yrange [-180:180]\nset ytics 90\nset key off\nplot ";
  bool first = true;
  for (int z = 0; z < Z; ++z) {
    if (hidden(z)) continue;
    const std::string color = colors[z % 9];
    g << (first ? "" : ", \\\n     ") << "$E" << z
      << " using 1:4:5 with yerrorbars pt 7 ps 0.5 lc rgb '" << color << "' notitle";
    first = false;
    if (drawn_model[z])
      g << ", $P" << z << " using 1:2 with lines lw 1.2 lc rgb '" << color << "' notitle";
  }
  g << "\nunset multiplot\n";
  RunGnuplot(file, g.str());
}

// Broadband estimates from the first R records, R = 1 … all: the share of H_z the records
// determine, the median 95 % bound and (with a model) the median and largest error, each
// relative to the largest |H_z| at its frequency — how many records a test needs.
void PlotConvergence(const std::string& file, const TimeData& data, const IdentifyOptions& o,
                     const std::vector<std::vector<cd>>& model) {
  std::ostringstream rows;
  for (size_t R = 1; R <= data.records.size(); ++R) {
    TimeData part = data;
    part.records.resize(R);
    const IdentifyResult r = IdentifyBroadband(part, o);
    std::vector<double> bounds, errors;
    size_t determined = 0, total = 0;
    for (size_t f = 0; f < r.frequencies.size(); ++f) {
      const IdentifiedFrequency& e = r.frequencies[f];
      double scale = 0;
      for (size_t z = 0; z < e.h.size(); ++z)
        scale = std::max(scale, model.empty() ? std::abs(e.h[z]) : std::abs(model[f][z]));
      for (size_t z = 0; z < e.h.size(); ++z) {
        ++total;
        if (!std::isfinite(std::abs(e.h[z])) || !(scale > 0)) continue;
        ++determined;
        if (std::isfinite(e.bound[z])) bounds.push_back(e.bound[z] / scale);
        if (!model.empty()) errors.push_back(std::abs(e.h[z] - model[f][z]) / scale);
      }
    }
    const auto median = [](std::vector<double> v) {
      if (v.empty()) return std::nan("");
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    const double largest =
        errors.empty() ? std::nan("") : *std::max_element(errors.begin(), errors.end());
    rows << R << " " << 100.0 * static_cast<double>(determined) / static_cast<double>(total) << " "
         << median(bounds) << " " << median(errors) << " " << largest << "\n";
  }
  std::ostringstream g;
  g << GnuplotTerminal(file, 900, 550) << "set output '" << file << "'\n$C << EOD\n"
    << rows.str() << "EOD\n"
    << "set title 'Broadband estimate against the number of records (relative to the largest "
       "|H_z| at each frequency)'\nset xlabel 'records'\nset ylabel 'relative to max |H_z|'\n"
    << "set logscale y\nset format y '10^{%L}'\nset y2label 'H_z determined  [%]'\n"
    << "set y2range [0:105]\nset y2tics\nset grid\nset key outside bottom center horizontal\n"
    << "set datafile missing 'nan'\n"
    << "plot $C using 1:3 with linespoints pt 7 lw 2 lc rgb '#1f77b4' title 'median 95 % bound'";
  if (!model.empty())
    g << ", $C using 1:4 with linespoints pt 5 lw 2 lc rgb '#d62728' title 'median error', "
         "$C using 1:5 with linespoints pt 9 lw 1.5 lc rgb '#ff7f0e' title 'largest error'";
  g << ", $C using 1:2 axes x1y2 with steps lw 1.5 lc rgb '#808080' title 'H_z determined (%)'\n";
  RunGnuplot(file, g.str());
}

// --delay CHANNEL=SECONDS: how late each named channel is sampled. Only what is relative to the
// rotor's phase counts, so a delayed tacho or encoder shifts the input and outputs the other way.
struct ChannelDelays {
  double input = 0, angle = 0;
  std::map<std::string, double> outputs;
};
ChannelDelays ParseDelays(const IdentifyArgs& args, const TimeData& data,
                          const IdentifyOptions& o) {
  ChannelDelays d;
  const std::string angle_spec = args.tacho.empty() ? args.angle : args.tacho;
  std::string angle_name;
  if (!angle_spec.empty())
    angle_name = data.auxiliary_names[static_cast<size_t>(
        ResolveChannel(angle_spec, data.auxiliary_names,
                       static_cast<int>(data.auxiliary_names.size()), "--tacho", "aux: channel"))];
  for (const std::string& spec : args.delays) {
    const size_t eq = spec.rfind('=');
    const std::optional<double> seconds =
        eq == std::string::npos ? std::nullopt : NumberIn(spec.substr(eq + 1));
    if (!seconds || !std::isfinite(*seconds))
      throw InputError("--delay " + spec + ": give CHANNEL=SECONDS (e.g. --delay Accel=2.4e-4)");
    const std::string name = spec.substr(0, eq);
    const auto& outputs = data.output_names;
    if (name == data.input_names[static_cast<size_t>(o.input)])
      d.input = *seconds;
    else if (std::find(outputs.begin(), outputs.end(), name) != outputs.end())
      d.outputs[name] = *seconds;
    else if (!angle_name.empty() && name == angle_name)
      d.angle = *seconds;
    else
      throw InputError("--delay " + spec + ": '" + name +
                       "' is neither the input, an output nor the --tacho/--angle channel");
  }
  return d;
}

// The outputs to estimate, as indices of the data's outputs: ltp's CSV names them among its
// out: columns; DAQ and UFF data hold just the channels --output chose, in its order.
std::vector<int> OutputIndices(const IdentifyArgs& args, const TimeData& data, bool ltp_format) {
  std::vector<int> outputs;
  for (size_t k = 0; k < args.outputs.size(); ++k) {
    const int index = ltp_format ? ResolveChannel(args.outputs[k], data.output_names,
                                                  static_cast<int>(data.output_names.size()),
                                                  "--output", "output")
                                 : static_cast<int>(k);
    if (std::count(outputs.begin(), outputs.end(), index) > 0)
      throw InputError("--output names '" + args.outputs[k] + "' twice");
    outputs.push_back(index);
  }
  return outputs;
}

// The estimate's options from the arguments: input, orders (at most 201) and the orders to
// plot (within them); the output is set per estimate.
IdentifyOptions IdentifyOptionsFrom(const IdentifyArgs& args, const TimeData& data,
                                    std::pair<int, int>* plotted) {
  IdentifyOptions o;
  o.input = ResolveChannel(args.input, data.input_names, static_cast<int>(data.input_names.size()),
                           "--input", "input");
  std::tie(o.min_order, o.max_order) = ParseOrderRange(args.orders, "--orders");
  if (static_cast<long>(o.max_order) - o.min_order > 200)
    throw InputError("--orders " + args.orders + ": at most 201 orders (e.g. -100:100)");
  *plotted = args.plot_orders.empty() ? std::make_pair(o.min_order, o.max_order)
                                      : ParseOrderRange(args.plot_orders, "--plot-orders");
  if (plotted->first < o.min_order || plotted->second > o.max_order)
    throw InputError("--plot-orders " + args.plot_orders + " lies outside the estimated orders " +
                     std::to_string(o.min_order) + ":" + std::to_string(o.max_order));
  return o;
}

// --compare: the scene, loaded once for every output (none without), its period checked
// against the data's unless the angle was measured.
std::optional<LoadedScene> ComparedScene(const IdentifyArgs& args, const TimeData& data,
                                         bool measured_speed) {
  if (args.compare.empty()) return std::nullopt;
  LoadedScene l = LoadSceneInput({args.compare}, args.set);
  if (!measured_speed && std::abs(l.system.period() - data.period) > 1e-9 * data.period)
    throw InputError("--compare: the scene's period " + Num(l.system.period(), 10) +
                     " s is not the data's " + Num(data.period, 10) + " s");
  return l;
}

// The compared scene's partial FRFs at the identified frequencies (empty without one).
std::vector<std::vector<cd>> ModelValues(const std::optional<LoadedScene>& scene,
                                         const IdentifyOptions& o, const IdentifyResult& r) {
  if (!scene) return {};
  PfrfOptions po;
  for (const auto& f : r.frequencies) po.frequencies_hz.push_back(f.excitation_hz);
  po.min_order = o.min_order;
  po.max_order = o.max_order;
  po.input = o.input;
  po.output = o.output;
  return ComputePartialFrf(scene->system, po).values;
}

// One output's estimate, with its name and the model's values (--compare; empty without).
struct OutputEstimate {
  std::string name;
  IdentifyOptions options;
  IdentifyResult result;
  std::vector<std::vector<cd>> model;
};

void WriteIdentifiedCsv(const std::string& path, const std::vector<OutputEstimate>& estimates) {
  std::ofstream out(path);
  out.precision(12);
  out << "output,f_exc_hz,z,re,im,abs,phase_deg,bound_95"
      << (estimates.front().model.empty() ? "" : ",model_re,model_im") << "\n";
  for (const auto& [name, o, r, model] : estimates)
    for (size_t f = 0; f < r.frequencies.size(); ++f)
      for (int z = 0; z <= o.max_order - o.min_order; ++z) {
        const cd h = r.frequencies[f].h[static_cast<size_t>(z)];
        out << name << "," << r.frequencies[f].excitation_hz << "," << z + o.min_order << ","
            << h.real() << "," << h.imag() << "," << std::abs(h) << ","
            << PhaseDeg(h.real(), h.imag()) << ","
            << r.frequencies[f].bound[static_cast<size_t>(z)];
        if (!model.empty())
          out << "," << model[f][static_cast<size_t>(z)].real() << ","
              << model[f][static_cast<size_t>(z)].imag();
        out << "\n";
      }
  if (!out) throw InputError("cannot write '" + path + "'");
}

// "+2", "0", "-1": an order as UFF ID lines name it.
std::string SignedOrder(int z) { return (z > 0 ? "+" : "") + std::to_string(z); }

// Per output and order, H_z as a complex FRF (function type 4) against the excitation frequency
// and its 95 % bound as a real function (type 0); the order in record 6's sequence field.
// Estimates that are NaN (not separable, under-determined) are left out of their function.
void WriteIdentifiedUff(const std::string& path, const TimeData& data,
                        const std::vector<OutputEstimate>& estimates, bool binary) {
  std::vector<Uff58Function> functions;
  for (const auto& [name, o, r, model] : estimates)
    for (int z = o.min_order; z <= o.max_order; ++z) {
      Uff58Function h, bound;
      h.function_type = 4;
      h.description =
          "H_" + SignedOrder(z) + " " + name + "/" + data.input_names[static_cast<size_t>(o.input)];
      h.id2 = "partial FRF of order z = " + SignedOrder(z) + " from time data (ltp identify)";
      h.sequence = z;
      h.response_name = name;
      h.response_node = o.output + 1;
      h.reference_name = data.input_names[static_cast<size_t>(o.input)];
      h.reference_node = o.input + 1;
      h.abscissa_type = 18;
      h.abscissa_label = "frequency";
      h.abscissa_unit = "Hz";
      bound = h;
      bound.function_type = 0;
      bound.description = "bound95 " + h.description;
      bound.id2 = "95 % bound on |error| of " + h.description;
      bound.x.clear();
      for (const IdentifiedFrequency& f : r.frequencies) {
        const cd v = f.h[static_cast<size_t>(z - o.min_order)];
        const double b = f.bound[static_cast<size_t>(z - o.min_order)];
        if (!std::isfinite(std::abs(v))) continue;
        h.x.push_back(f.excitation_hz);
        h.complex.push_back(v);
        if (!std::isfinite(b)) continue;
        bound.x.push_back(f.excitation_hz);
        bound.real.push_back(b);
      }
      if (!h.x.empty()) functions.push_back(h);
      if (!bound.x.empty()) functions.push_back(bound);
    }
  if (functions.empty()) throw InputError("--uff: no estimate has a value to write");
  WriteUff58(path, functions, binary);
}

// FILE.svg for one output; FILE-NAME.svg per output when there are several.
std::string PerOutputFile(const std::string& file, const std::string& output, bool several) {
  if (!several) return file;
  const std::filesystem::path p(file);
  return (p.parent_path() / (p.stem().string() + "-" + output + p.extension().string())).string();
}

json IdentifiedJson(const std::string& name, const std::string& method, const TimeData& data,
                    const IdentifyOptions& o, const IdentifyResult& r,
                    const std::vector<std::vector<cd>>& model,
                    const std::optional<MeasuredSpeeds>& speeds) {
  const int Z = o.max_order - o.min_order + 1;
  json freqs = json::array();
  for (size_t f = 0; f < r.frequencies.size(); ++f) {
    json h = json::array();
    for (int z = 0; z < Z; ++z) {
      const cd v = r.frequencies[f].h[static_cast<size_t>(z)];
      json e = {{"z", z + o.min_order},
                {"re", JsonNumber(v.real())},
                {"im", JsonNumber(v.imag())},
                {"bound_95", JsonNumber(r.frequencies[f].bound[static_cast<size_t>(z)])}};
      if (!model.empty())
        e["model"] = {JsonNumber(model[f][static_cast<size_t>(z)].real()),
                      JsonNumber(model[f][static_cast<size_t>(z)].imag())};
      if (!r.frequencies[f].condition.empty()) {
        e["condition"] = JsonNumber(r.frequencies[f].condition[static_cast<size_t>(z)]);
        e["quality"] = JsonNumber(r.frequencies[f].quality[static_cast<size_t>(z)]);
      }
      h.push_back(e);
    }
    freqs.push_back({{"excitation_hz", r.frequencies[f].excitation_hz},
                     {"speed_rad_s", JsonNumber(r.frequencies[f].speed)},
                     {"separable", r.frequencies[f].separable},
                     {"noise_rms", JsonNumber(r.frequencies[f].noise)},
                     {"H", h}});
  }
  json out = {{"data", name},
              {"method", method},
              {"period_s", data.period},
              {"input", o.input},
              {"output", o.output},
              {"output_name", data.output_names[static_cast<size_t>(o.output)]},
              {"records", data.records.size()},
              {"frequencies", freqs},
              {"diagnostics", Texts(r.diagnostics)}};
  if (speeds)
    out["measured_speed_rad_s"] = {
        {"min", speeds->min_speed}, {"max", speeds->max_speed}, {"mean", speeds->mean_speed}};
  return out;
}

// The table: one line per frequency and order (or why the line has no value), then the notes.
void PrintIdentified(const std::string& name, const std::string& method, bool broadband,
                     const IdentifyArgs& args, const TimeData& data, const IdentifyOptions& o,
                     const IdentifyResult& r, const std::vector<std::vector<cd>>& model,
                     const std::optional<MeasuredSpeeds>& speeds) {
  const int Z = o.max_order - o.min_order + 1;
  std::cout << "Partial FRFs identified from " << name
            << (broadband && method == "broadband"
                    ? " (broadband: least squares across " + std::to_string(data.records.size()) +
                          " records per response line, §4.2): " +
                          std::to_string(r.frequencies.size()) + " excited frequencies"
                    : " (step-sine, eq. 47): " + std::to_string(r.frequencies.size()) + " records")
            << ", T = " << Num(data.period, 10) << " s, output "
            << data.output_names[static_cast<size_t>(o.output)] << " / input "
            << data.input_names[static_cast<size_t>(o.input)] << "\n"
            << (speeds ? "  rotor phase from --" +
                             std::string(args.tacho.empty() ? "angle" : "tacho") + ": speed " +
                             Num(speeds->min_speed, 6) + " … " + Num(speeds->max_speed, 6) +
                             " rad/s, mean " + Num(speeds->mean_speed, 7) + " (2π/T of the data: " +
                             Num(2 * std::numbers::pi / data.period, 7) + ")\n"
                       : std::string())
            << "    f_exc [Hz]    z       |H_z|    ± 95 %     phase [°]"
            << (model.empty() ? "" : "   |model − H_z|") << "\n";
  for (size_t f = 0; f < r.frequencies.size(); ++f)
    for (int z = 0; z < Z; ++z) {
      const cd h = r.frequencies[f].h[static_cast<size_t>(z)];
      if (!r.frequencies[f].separable && std::isnan(h.real())) {
        std::cout << Num(r.frequencies[f].excitation_hz, 7, 14) << Num(z + o.min_order, 3, 5)
                  << "   not separable from one record (a multiple of fp/2)\n";
        continue;
      }
      if (std::isnan(h.real())) {
        std::cout << Num(r.frequencies[f].excitation_hz, 7, 14) << Num(z + o.min_order, 3, 5)
                  << "   under-determined: too few records for the unknowns of its line\n";
        continue;
      }
      std::cout << Num(r.frequencies[f].excitation_hz, 7, 14) << Num(z + o.min_order, 3, 5)
                << Num(std::abs(h), 4, 12)
                << Num(r.frequencies[f].bound[static_cast<size_t>(z)], 2, 10)
                << Num(PhaseDeg(h.real(), h.imag()), 4, 14);
      if (!model.empty()) std::cout << Num(std::abs(model[f][static_cast<size_t>(z)] - h), 2, 16);
      std::cout << "\n";
    }
  for (const Diagnostic& d : r.diagnostics) std::cout << "  note: " << d.text << "\n";
}

int RunIdentify(const IdentifyArgs& args) {
  if (!args.period.empty() && !args.rotor_speed.empty())
    throw InputError("--period and --rotor-speed: give one of them");
  const double rotor_speed = PositiveOption(args.rotor_speed, "--rotor-speed");
  const double period = !args.period.empty()
                            ? PositiveOption(args.period, "--period")
                            : (rotor_speed > 0 ? 2 * std::numbers::pi / rotor_speed : 0);
  const bool measured_angle = !args.tacho.empty() || !args.angle.empty();
  bool ltp_format = false;
  TimeData data = ReadTimeData(args, period, !measured_angle, &ltp_format);
  std::string name = args.files.front();
  for (size_t f = 1; f < args.files.size(); ++f) name += (f == 1 ? ", " : ", ") + args.files[f];
  const std::optional<MeasuredSpeeds> speeds = MeasureAngles(args, data);
  std::pair<int, int> plotted;
  const IdentifyOptions options = IdentifyOptionsFrom(args, data, &plotted);
  // auto: broadband when every record is (excitation_hz = 0, as ltp simulate writes them).
  // DAQ files write no frequency: step-sine records whose input says it.
  bool broadband = ltp_format;
  for (const TimeRecord& rec : data.records) broadband = broadband && rec.excitation_hz == 0;
  const std::string method =
      args.method == "auto" ? (broadband ? "broadband" : "stepsine") : args.method;
  if (!args.convergence.empty() && method != "broadband")
    throw InputError("--convergence: needs broadband records (it adds them one by one)");
  const ChannelDelays delays = ParseDelays(args, data, options);
  const std::optional<LoadedScene> compared = ComparedScene(args, data, speeds.has_value());
  std::vector<OutputEstimate> estimates;
  for (const int output : OutputIndices(args, data, ltp_format)) {
    OutputEstimate e{data.output_names[static_cast<size_t>(output)], options, {}, {}};
    e.options.output = output;
    e.options.input_delay = delays.input - delays.angle;
    e.options.output_delay =
        (delays.outputs.count(e.name) ? delays.outputs.at(e.name) : 0.0) - delays.angle;
    e.result = method == "broadband" ? IdentifyBroadband(data, e.options)
                                     : IdentifyStepSine(data, e.options);
    e.model = ModelValues(compared, e.options, e.result);
    estimates.push_back(std::move(e));
  }
  const bool several = estimates.size() > 1;
  std::vector<std::string> written;
  if (!args.csv.empty()) {
    WriteIdentifiedCsv(args.csv, estimates);
    written.push_back(args.csv);
  }
  if (!args.uff.empty()) {
    WriteIdentifiedUff(args.uff, data, estimates, args.binary);
    written.push_back(args.uff);
  }
  for (const OutputEstimate& e : estimates) {
    if (!args.plot.empty()) {
      written.push_back(PerOutputFile(args.plot, e.name, several));
      PlotIdentified(written.back(), e.result, e.model,
                     "Partial FRFs from time data: " + name + (several ? ", " + e.name : ""),
                     method, plotted);
    }
    if (!args.convergence.empty()) {
      written.push_back(PerOutputFile(args.convergence, e.name, several));
      PlotConvergence(written.back(), data, e.options, e.model);
    }
  }
  if (args.json) {
    json out = json::array();
    for (const OutputEstimate& e : estimates)
      out.push_back(IdentifiedJson(name, method, data, e.options, e.result, e.model, speeds));
    std::cout << (several ? out : out[0]).dump(2) << "\n";
    return 0;
  }
  for (const OutputEstimate& e : estimates)
    PrintIdentified(name, method, broadband, args, data, e.options, e.result, e.model, speeds);
  for (const std::string& file : written) std::cout << "  wrote " << file << "\n";
  return 0;
}

}  // namespace

Command AddIdentifyCommand(CLI::App& app) {
  static IdentifyArgs args;
  args = IdentifyArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "identify",
      "partial FRFs from step-sine or broadband time data (CSV of ltp simulate or a rig)");
  cmd->add_option("data", args.files,
                  "ltp's time-data CSV, or a DAQ's CSV files (one step-sine record each: a "
                  "header of channel names, a time column or --sample-rate)")
      ->required();
  cmd->add_option("--sample-rate", args.sample_rate,
                  "DAQ files without a time column: samples per second");
  cmd->add_option("--method", args.method,
                  "auto (broadband when every record is), stepsine or broadband")
      ->check(CLI::IsMember({"auto", "stepsine", "broadband"}))
      ->capture_default_str();
  cmd->add_option("--period", args.period, "period T (s), when the file does not give it");
  cmd->add_option("--rotor-speed", args.rotor_speed, "or the rotor speed (rad/s): T = 2π/Ω");
  cmd->add_option("--tacho", args.tacho,
                  "aux: channel of a tacho (pulses): the rotor's phase is measured, so the speed "
                  "may differ from 2π/T and drift (step-sine)");
  cmd->add_option("--pulses-per-period", args.pulses_per_period, "tacho pulses per period T")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--tacho-angle", args.tacho_angle_deg,
                  "the system's phase (degrees) when a tacho pulse rises through mid-level")
      ->capture_default_str();
  cmd->add_option("--angle", args.angle,
                  "aux: channel of an encoder giving the phase in rad (wrapped or not)");
  cmd->add_option("--input", args.input, "input (index or name)")->capture_default_str();
  cmd->add_option("--delay", args.delays,
                  "CHANNEL=SECONDS: the channel is sampled this much late (an anti-alias filter's "
                  "group delay, a DAQ's skew); repeat per channel");
  cmd->add_option("--output", args.outputs,
                  "output(s) (index or name; several: --output a,b or repeated), each estimated "
                  "from the same records")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--orders", args.orders, "ZMIN:ZMAX")->capture_default_str();
  cmd->add_option("--compare", args.compare,
                  "a scene whose model values to set beside the estimates");
  cmd->add_option("--set", args.set, "NAME=VALUE for the --compare scene (as the data were made)");
  cmd->add_option("--csv", args.csv, "one row per output, frequency and order");
  cmd->add_option("--uff", args.uff,
                  "H_z and its 95 % bound per output and order as UFF 58 functions (FILE.uff)");
  cmd->add_flag("--binary", args.binary, "--uff as binary dataset 58b");
  cmd->add_option("--plot", args.plot,
                  "|H_z| with 95 % bounds (and the model) against frequency (FILE.svg|.png)");
  cmd->add_option("--plot-orders", args.plot_orders,
                  "ZMIN:ZMAX: the orders --plot draws (default: all estimated)");
  cmd->add_option("--convergence", args.convergence,
                  "broadband: bounds (and errors against --compare) as records are added "
                  "(FILE.svg|.png)");
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  return {cmd, [] { return RunIdentify(args); }};
}

}  // namespace ltp::cli
