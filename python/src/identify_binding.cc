// ltp.simulate and ltp.identify: `ltp simulate` and `ltp identify` for a notebook, on numpy
// arrays — records as lists of 1-D arrays (one per step-sine frequency or broadband
// realisation), the rotor's phase from a tacho or an encoder array (htf/rotor_angle.h).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "binding.h"
#include "diagnostic_properties.h"
#include "ltp/core/error.h"
#include "ltp/htf/identify.h"
#include "ltp/htf/rotor_angle.h"
#include "ltp/htf/simulate.h"

namespace ltp::python {

namespace {

constexpr const char* kRealSamples = "measured samples are real numbers";

// Records given as one 1-D array (one record) or a sequence of them, each finite.
std::vector<Eigen::VectorXd> RecordArrays(const py::object& value, const std::string& what) {
  std::vector<Eigen::VectorXd> out;
  const auto one = [&](const py::handle& h, size_t k) {
    const py::array a = RealValued(
        h, [&] { return what + "[" + std::to_string(k) + "]"; }, kRealSamples);
    if (!a || a.ndim() != 1)
      throw InputError(what + ": each record must be a 1-D array of samples");
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!d) throw InputError(what + ": not numbers");
    Eigen::VectorXd v(static_cast<Eigen::Index>(d.size()));
    for (py::ssize_t i = 0; i < d.size(); ++i) v(static_cast<Eigen::Index>(i)) = d.at(i);
    out.push_back(std::move(v));
  };
  const py::array as_array = RealValued(
      value, [&] { return what; }, kRealSamples);
  if (as_array && as_array.ndim() == 1) {
    one(value, 0);
    return out;
  }
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value))
    throw InputError(what + ": a 1-D array (one record) or a list of them");
  size_t k = 0;
  for (const py::handle h : value) one(h, k++);
  if (out.empty()) throw InputError(what + ": no records");
  return out;
}

std::vector<py::array_t<double>> ArraysOf(const std::vector<Eigen::VectorXd>& v) {
  std::vector<py::array_t<double>> out;
  for (const Eigen::VectorXd& x : v)
    out.push_back(py::array_t<double>(static_cast<py::ssize_t>(x.size()), x.data()));
  return out;
}

// What ltp.simulate returns: the records as lists of arrays.
struct SimulatedRecords {
  SimulationResult result;
  int input = 0, output = 0;  // the excited input and the output shown as `output`
};

std::vector<Eigen::VectorXd> TimeColumns(const TimeData& d) {
  std::vector<Eigen::VectorXd> out;
  for (const TimeRecord& r : d.records)
    out.push_back(
        Eigen::Map<const Eigen::VectorXd>(r.time.data(), static_cast<Eigen::Index>(r.time.size())));
  return out;
}

template <class Get>
std::vector<py::array_t<double>> Columns(const TimeData& d, Get get) {
  std::vector<Eigen::VectorXd> out;
  for (const TimeRecord& r : d.records) out.push_back(get(r));
  return ArraysOf(out);
}

// What ltp.identify returns, with the speeds the angle was measured at (if it was).
struct IdentifiedRecords {
  IdentifyResult result;
  std::optional<MeasuredSpeeds> speeds;
  double period = 0;
  std::string method;
};

// One number of every identified frequency, as an array.
py::array_t<double> PerFrequency(const IdentifiedRecords& r, double IdentifiedFrequency::*field) {
  std::vector<double> v;
  for (const IdentifiedFrequency& x : r.result.frequencies) v.push_back(x.*field);
  return RealArray(v);
}

void BindSimulationResult(py::module_& m) {
  py::class_<SimulatedRecords>(m, "SimulationResult", R"doc(
Time data of ltp.simulate: lists with one 1-D array per record (one per step-sine frequency, or
per broadband realisation), ready for ltp.identify(r.time, r.input, r.output, period=r.period).)doc")
      .def_property_readonly(
          "time", [](const SimulatedRecords& s) { return ArraysOf(TimeColumns(s.result.data)); },
          "sample times (s) per record")
      .def_property_readonly(
          "input",
          [](const SimulatedRecords& s) {
            return Columns(s.result.data, [&](const TimeRecord& r) -> Eigen::VectorXd {
              return r.inputs.col(s.input);
            });
          },
          "the excited input per record (with its measurement noise)")
      .def_property_readonly(
          "output",
          [](const SimulatedRecords& s) {
            return Columns(s.result.data, [&](const TimeRecord& r) -> Eigen::VectorXd {
              return r.outputs.col(s.output);
            });
          },
          "the output chosen by simulate(output=) per record (with its noise)")
      .def_property_readonly(
          "tacho",
          [](const SimulatedRecords& s) -> py::object {
            if (s.result.data.auxiliary_names.empty()) return py::none();
            return py::cast(Columns(s.result.data, [](const TimeRecord& r) -> Eigen::VectorXd {
              return r.auxiliary.col(0);
            }));
          },
          "the tacho channel per record (tacho=True), else None")
      .def_property_readonly(
          "excitation_hz",
          [](const SimulatedRecords& s) {
            std::vector<double> f;
            for (const TimeRecord& r : s.result.data.records) f.push_back(r.excitation_hz);
            return RealArray(f);
          },
          "each record's frequency on the record's grid (0: broadband)")
      .def_property_readonly(
          "period", [](const SimulatedRecords& s) { return s.result.data.period; }, "T (s)")
      .def_property_readonly(
          "settle_time", [](const SimulatedRecords& s) { return s.result.settle_time; },
          "s integrated before each record")
      .def_property_readonly(
          "diagnostics", [](const SimulatedRecords& s) { return Texts(s.result.diagnostics); },
          "e.g. frequencies moved to the record's grid")
      .def_property_readonly(
          "diagnostic_codes",
          [](const SimulatedRecords& s) { return CodeNames(s.result.diagnostics); },
          kDiagnosticCodesDoc);
}

// ltp.simulate: the options checked as the CLI checks them; the records made without the GIL.
SimulatedRecords LtpSimulate(const System& system, const py::object& freq, const py::object& input,
                             const py::object& output, const std::string& excitation, int periods,
                             int samples_per_period, Real amplitude, std::optional<Real> noise,
                             std::optional<Real> input_noise, Real speed_offset, Real speed_ramp,
                             bool tacho, std::uint64_t seed, int records) {
  if (system.callbacks)
    throw InputError(
        "simulate: a system behind Python callables is not supported (its "
        "RKF78 steps would take the GIL per evaluation); build it from Fourier "
        "coefficients or a scene");
  SimulateOptions o;
  const SystemLabels& labels = system.system.labels();
  o.input = ChannelFrom(input, labels.inputs, system.system.inputs(), "input");
  const int out = ChannelFrom(output, labels.outputs, system.system.outputs(), "output");
  o.frequencies_hz = FrequenciesFrom(freq);
  o.periods = periods;
  o.samples_per_period = samples_per_period;
  o.amplitude = amplitude;
  o.noise_snr_db = noise.value_or(std::numeric_limits<double>::infinity());
  o.input_noise_snr_db = input_noise.value_or(std::numeric_limits<double>::infinity());
  o.speed_offset = speed_offset / 100;
  o.speed_ramp = speed_ramp / 100;
  o.tacho = tacho;
  o.seed = seed;
  o.records = records;
  if (excitation != "stepsine" && excitation != "multisine")
    throw InputError("excitation must be stepsine or multisine, got '" + excitation + "'");
  o.Validate();
  SimulatedRecords r;
  r.input = o.input;
  r.output = out;
  r.result = WithoutGil(system, [&] {
    return excitation == "stepsine" ? SimulateStepSine(system.system, o)
                                    : SimulateMultisine(system.system, o);
  });
  return r;
}

void BindSimulateFunction(py::module_& m) {
  const SimulateOptions defaults;
  m.def("simulate", &LtpSimulate, py::arg("system"), py::arg("freq"), py::kw_only(),
        py::arg("input") = 0, py::arg("output") = 0, py::arg("excitation") = "stepsine",
        py::arg("periods") = defaults.periods,
        py::arg("samples_per_period") = defaults.samples_per_period,
        py::arg("amplitude") = defaults.amplitude, py::arg("noise") = py::none(),
        py::arg("input_noise") = py::none(), py::arg("speed_offset") = 0.0,
        py::arg("speed_ramp") = 0.0, py::arg("tacho") = false, py::arg("seed") = defaults.seed,
        py::arg("records") = defaults.records,
        R"doc(
Time data of a test: `ltp simulate` as a function, with its options and defaults.

  freq          frequencies (Hz): 'F0:F1:DF' or an array; each moved to whole cycles of the record
  excitation    stepsine (one record per frequency) or multisine (all at once, `records` times)
  noise, input_noise   white noise SNR (dB) on the output and on the recorded input (None: none)
  speed_offset, speed_ramp   a rig's rotor: % faster than the model, and % more over each record
  tacho         record a once-per-period tacho (rising through mid-level at phase 0)

Returns a SimulationResult (lists of arrays per record).

    s = ltp.simulate(ltp.scene("mathieu", a=2, c=0.2, q=0.3), "0.05:0.6:0.05", noise=30,
                     speed_offset=1, tacho=True)
    r = ltp.identify(s.time, s.input, s.output, tacho=s.tacho))doc");
}

void BindIdentifyResult(py::module_& m) {
  py::class_<IdentifiedRecords>(m, "IdentifyResult", R"doc(
Partial FRFs estimated from time data (ltp.identify): H over frequency and order, each with its
95 % bound.)doc")
      .def_property_readonly(
          "excitation_hz",
          [](const IdentifiedRecords& r) {
            return PerFrequency(r, &IdentifiedFrequency::excitation_hz);
          },
          "the frequencies (Hz), as measured from the inputs (step-sine)")
      .def_property_readonly(
          "orders",
          [](const IdentifiedRecords& r) {
            std::vector<std::int64_t> z;
            for (int k = r.result.min_order; k <= r.result.max_order; ++k) z.push_back(k);
            return py::array_t<std::int64_t>(static_cast<py::ssize_t>(z.size()), z.data());
          },
          "z of each column")
      .def_property_readonly(
          "H",
          [](const IdentifiedRecords& r) {
            std::vector<std::vector<Complex>> rows;
            for (const IdentifiedFrequency& x : r.result.frequencies) rows.push_back(x.h);
            return ComplexTable(rows,
                                static_cast<size_t>(r.result.max_order - r.result.min_order + 1));
          },
          "H_z, shape (frequencies, orders); NaN where not separable or under-determined")
      .def_property_readonly(
          "bound",
          [](const IdentifiedRecords& r) {
            std::vector<std::vector<double>> rows;
            for (const IdentifiedFrequency& x : r.result.frequencies) rows.push_back(x.bound);
            return RealTable(rows,
                             static_cast<size_t>(r.result.max_order - r.result.min_order + 1));
          },
          "95 % bound on |error| of each H_z")
      .def_property_readonly(
          "speed",
          [](const IdentifiedRecords& r) { return PerFrequency(r, &IdentifiedFrequency::speed); },
          "step-sine: each record's mean dθ/dt (rad/s)")
      .def_property_readonly(
          "noise",
          [](const IdentifiedRecords& r) { return PerFrequency(r, &IdentifiedFrequency::noise); },
          "rms of the noise left by the fit (output units)")
      .def_readonly("period", &IdentifiedRecords::period,
                    "T (s): given, or 2π / the measured speed")
      .def_readonly("method", &IdentifiedRecords::method, "stepsine or broadband")
      .def_property_readonly(
          "measured_speed",
          [](const IdentifiedRecords& r) -> py::object {
            if (!r.speeds) return py::none();
            py::dict d;
            d["min"] = r.speeds->min_speed;
            d["max"] = r.speeds->max_speed;
            d["mean"] = r.speeds->mean_speed;
            return d;
          },
          "{'min', 'max', 'mean'} rad/s from the tacho or the encoder, else None")
      .def_property_readonly(
          "diagnostics", [](const IdentifiedRecords& r) { return Texts(r.result.diagnostics); },
          "what the data say about themselves (speed, gaps, clipping, …), one line each")
      .def_property_readonly(
          "diagnostic_codes",
          [](const IdentifiedRecords& r) { return CodeNames(r.result.diagnostics); },
          kDiagnosticCodesDoc);
}

// The records as the library's time data, one TimeRecord each. @throws InputError when a record's
// arrays differ in length.
TimeData RecordsData(const std::vector<Eigen::VectorXd>& t, const std::vector<Eigen::VectorXd>& u,
                     const std::vector<Eigen::VectorXd>& y, const std::vector<Eigen::VectorXd>& aux,
                     const std::vector<double>& frequencies, std::optional<double> period) {
  TimeData data;
  data.period = period.value_or(0);
  data.input_names = {"input"};
  data.output_names = {"output"};
  for (size_t k = 0; k < t.size(); ++k) {
    if (u[k].size() != t[k].size() || y[k].size() != t[k].size() ||
        (!aux.empty() && aux[k].size() != t[k].size()))
      throw InputError("record " + std::to_string(k) + ": the arrays differ in length");
    TimeRecord r;
    r.time.assign(t[k].data(), t[k].data() + t[k].size());
    r.inputs = u[k];
    r.outputs = y[k];
    if (!aux.empty()) r.auxiliary = aux[k];
    r.excitation_hz = frequencies[k];
    data.records.push_back(std::move(r));
  }
  return data;
}

// ltp.identify: the records checked against each other, the rotor's phase measured when given;
// the estimation runs without the GIL.
IdentifiedRecords LtpIdentify(const py::object& time, const py::object& input,
                              const py::object& output, std::optional<Real> period_in,
                              const py::object& excitation_hz, const py::object& tacho,
                              const py::object& angle, int pulses_per_period, Real tacho_angle,
                              const py::object& orders, const std::string& method, Real input_delay,
                              Real output_delay) {
  const std::optional<double> period = period_in ? std::optional<double>(*period_in) : std::nullopt;
  const std::vector<Eigen::VectorXd> t = RecordArrays(time, "time");
  const std::vector<Eigen::VectorXd> u = RecordArrays(input, "input");
  const std::vector<Eigen::VectorXd> y = RecordArrays(output, "output");
  if (u.size() != t.size() || y.size() != t.size())
    throw InputError("time, input and output must hold the same number of records (" +
                     std::to_string(t.size()) + ", " + std::to_string(u.size()) + ", " +
                     std::to_string(y.size()) + ")");
  if (!tacho.is_none() && !angle.is_none())
    throw InputError("tacho and angle: give one source of the rotor's phase");
  const py::object& phase = tacho.is_none() ? angle : tacho;
  const std::vector<Eigen::VectorXd> aux =
      phase.is_none() ? std::vector<Eigen::VectorXd>{}
                      : RecordArrays(phase, tacho.is_none() ? "angle" : "tacho");
  if (!aux.empty() && aux.size() != t.size())
    throw InputError("the phase channel must hold one array per record");
  std::vector<double> frequencies(t.size(), 0.0);
  if (!excitation_hz.is_none()) {
    frequencies = FrequenciesFrom(excitation_hz);
    if (frequencies.size() != t.size())
      throw InputError("excitation_hz: one frequency per record (" + std::to_string(t.size()) +
                       ")");
  }
  if (period && !(*period > 0 && std::isfinite(*period)))
    throw InputError("period must be finite and > 0");
  if (!period && aux.empty())
    throw InputError("give the period (s), or the rotor's phase (tacho= or angle=)");
  TimeData data = RecordsData(t, u, y, aux, frequencies, period);
  IdentifyOptions o;
  std::tie(o.min_order, o.max_order) = OrdersFrom(orders);
  o.input_delay = input_delay;
  o.output_delay = output_delay;
  o.Validate();
  IdentifiedRecords out;
  if (!aux.empty()) {
    AngleChannel source;
    source.kind = tacho.is_none() ? AngleChannel::Kind::kEncoder : AngleChannel::Kind::kTacho;
    source.tacho.pulses_per_period = pulses_per_period;
    source.tacho.pulse_angle = tacho_angle;
    out.speeds = SetMeasuredAngles(data, source);
  }
  out.method = method;
  if (method != "stepsine" && method != "broadband")
    throw InputError("method must be stepsine or broadband, got '" + method + "'");
  out.period = data.period;
  py::gil_scoped_release release;
  out.result = out.method == "broadband" ? IdentifyBroadband(data, o) : IdentifyStepSine(data, o);
  return out;
}

void BindIdentifyFunction(py::module_& m) {
  m.def("identify", &LtpIdentify, py::arg("time"), py::arg("input"), py::arg("output"),
        py::kw_only(), py::arg("period") = py::none(), py::arg("excitation_hz") = py::none(),
        py::arg("tacho") = py::none(), py::arg("angle") = py::none(),
        py::arg("pulses_per_period") = 1, py::arg("tacho_angle") = 0.0, py::arg("orders") = "-2:2",
        py::arg("method") = "stepsine", py::arg("input_delay") = 0.0, py::arg("output_delay") = 0.0,
        R"doc(
Partial FRFs from time data: `ltp identify` on numpy arrays.

  time, input, output   one 1-D array per record (a list), or one array for one record
  period                T (s); may be left out when tacho= or angle= gives the phase
  excitation_hz         each record's frequency as logged (default: found from its input)
  tacho, angle          the rotor's phase per record: a tacho signal (pulses) or an encoder's
                        angle (rad); the speed may then differ from 2π/T and drift
  pulses_per_period, tacho_angle   tacho pulses per period T; the phase (rad) at a pulse
  orders                'ZMIN:ZMAX', an int or a pair
  method                stepsine (least squares on the lines ωt + zθ(t); docs/rig-data.md) or
                        broadband (records of one multisine, excitation_hz all 0)
  input_delay, output_delay   how late (s) each channel is sampled against the rotor's phase
                        (an anti-alias filter's group delay, a DAQ's skew): undone in the fit

Returns an IdentifyResult (H, bound, excitation_hz, speed, diagnostics).)doc");
}

}  // namespace

void BindIdentify(py::module_& m) {
  BindSimulationResult(m);
  BindSimulateFunction(m);
  BindIdentifyResult(m);
  BindIdentifyFunction(m);
}

}  // namespace ltp::python
