// MBC3: multi-blade coordinates with azimuth averaging for OpenFAST linearisations
// (formulation and sources in ltp/openfast/mbc3.h).
#include "ltp/openfast/mbc3.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <regex>

#include "ltp/core/error.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/core/mode_description.h"
#include "ltp/core/multiblade.h"
#include "ltp/core/text.h"

namespace ltp {

std::string_view ToString(MbcMode::Kind kind) {
  switch (kind) {
    case MbcMode::Kind::kOscillatory:
      return "oscillatory";
    case MbcMode::Kind::kReal:
      return "real";
    case MbcMode::Kind::kRigidBody:
      return "rigid-body";
  }
  return "?";
}
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;

// Removes ElastoDyn's "(internal DOF index = DOF_BF(1,1))": it repeats the blade number in
// another place (openfast_toolbox does the same before matching).
std::string StripInternalIndex(const std::string& description) {
  const std::string marker = "(internal DOF index =";
  const auto at = description.find(marker);
  if (at == std::string::npos) return description;
  int depth = 0;
  size_t end = at;
  for (; end < description.size(); ++end) {
    if (description[end] == '(') ++depth;
    if (description[end] == ')' && --depth == 0) break;
  }
  std::string s = description.substr(0, at);
  if (end < description.size()) s += description.substr(end + 1);
  // Tidy "DOF , m" → "DOF, m" and doubled spaces.
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == ' ' && i + 1 < s.size() && (s[i + 1] == ' ' || s[i + 1] == ',')) continue;
    out += s[i];
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string CoordinateWord(int blades, int c) {
  if (c == 0) return "collective";
  if (blades % 2 == 0 && c == blades - 1) return "differential";
  const int h = (c + 1) / 2;
  const std::string word = c % 2 == 1 ? "cosine" : "sine";
  return h == 1 ? word : word + " " + std::to_string(h);
}

std::string Percent(double share) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.0f%%", 100 * share);
  return buf;
}

// The rate group of a second-order DOF group must list the rates of the same DOFs, blade by
// blade. @throws InputError otherwise.
void CheckRateGroups(const BladeCoordinates& c, const std::vector<int>& rate_of,
                     const std::vector<LinChannel>& states) {
  for (size_t i = 0; i < rate_of.size(); ++i)
    if (rate_of[i] >= 0 && (c.group_of[i] >= 0) != (c.group_of[rate_of[i]] >= 0))
      throw InputError("state '" + states[i].description + "' and its displacement '" +
                       states[rate_of[i]].description +
                       "' disagree on the rotating frame: both or neither must be blade states");
  for (const auto& g : c.groups) {
    if (rate_of[g[0]] < 0) continue;
    const int dg = c.group_of[rate_of[g[0]]];
    for (size_t b = 0; b < g.size(); ++b) {
      const int d = rate_of[g[b]];
      if (d < 0 || dg < 0 || c.group_of[d] != dg || c.blade_of[d] != static_cast<int>(b))
        throw InputError("rotating-frame state '" + states[g[b]].description +
                         "' is the rate of a DOF that is not in the matching blade tuple: the "
                         "displacements and rates are not listed in the same order");
    }
  }
}

// The mode's participation per displacement: p_d plus the participation of d's rate (a
// second-order DOF takes part through both; docs/mode-descriptions.md).
Eigen::VectorXcd ParticipationPerDisplacement(const std::vector<int>& rate_of,
                                              const Eigen::VectorXcd& participation) {
  Eigen::VectorXcd p = Eigen::VectorXcd::Zero(participation.size());
  for (Eigen::Index i = 0; i < participation.size(); ++i)
    p(rate_of[i] >= 0 ? rate_of[i] : i) += participation(i);
  return p;
}

// The mode's description: its participation summed per coordinate family (a fixed-frame
// state, a collective, or a cosine/sine pair, each with its rates), |sum| over the sum of the
// families' |sum|, largest first; a cyclic pair is named by its whirl direction when the phase
// between cosine and sine says so.
void DescribeMode(const BladeCoordinates& c, const std::vector<int>& rate_of,
                  const std::vector<LinChannel>& states, const Mbc3Options& options, MbcMode& m) {
  const int n = static_cast<int>(states.size());
  const Eigen::VectorXcd& v = m.eigenvector;
  const Eigen::VectorXcd p = ParticipationPerDisplacement(rate_of, m.participation);
  struct Family {
    std::string name;
    double share = 0;
    std::string whirl;
  };
  std::vector<Family> families;
  std::vector<bool> done(n, false);
  for (int i = 0; i < n; ++i) {
    if (rate_of[i] >= 0 || done[i]) continue;
    done[i] = true;
    Family f{WithoutUnit(states[i].description), std::abs(p[i]), ""};
    const int g = c.group_of[i], b = c.blade_of[i];
    const bool cyclic = g >= 0 && b > 0 && !(c.blades % 2 == 0 && b == c.blades - 1);
    if (cyclic) {
      const int cos_index = c.groups[g][b % 2 == 1 ? b : b - 1];
      const int sin_index = c.groups[g][b % 2 == 1 ? b + 1 : b];
      done[cos_index] = done[sin_index] = true;
      f.share = std::abs(p[cos_index] + p[sin_index]);
      // Pattern a_c cos φ + a_s sin φ in the fixed frame, times e^{jωt}, ω > 0: it travels
      // with the rotor (forward) when a_s lags a_c by 90°, Im(conj(a_c) a_s) < 0.
      const double w = std::imag(std::conj(v[cos_index]) * v[sin_index]);
      const double scale = std::abs(v[cos_index]) * std::abs(v[sin_index]);
      if (m.eigenvalue.imag() > 0 && scale > 0 && std::abs(w) >= 0.5 * scale)
        f.whirl = w < 0 ? "forward" : "backward";
      const int h = (b + 1) / 2;
      std::string label = "(cyclic";
      if (h > 1) label += " " + std::to_string(h);
      // Wind energy says forward/backward whirl, helicopters and rotordynamics progressive/
      // regressive: both, so a reader from either field finds the word.
      if (!f.whirl.empty())
        label += f.whirl == "forward" ? ", FW whirl: progressive" : ", BW whirl: regressive";
      label += ")";
      std::string base = WithoutUnit(states[cos_index].description);
      const std::string cosine = "(" + CoordinateWord(c.blades, 2 * h - 1) + ")";
      const auto at = base.find(cosine);
      if (at != std::string::npos) base.replace(at, cosine.size(), label);
      f.name = base;
    }
    families.push_back(std::move(f));
  }
  double total = 0;
  for (const Family& f : families) total += f.share;
  if (!(total > 0) || !std::isfinite(total)) return;
  for (Family& f : families) f.share /= total;
  std::stable_sort(families.begin(), families.end(),
                   [](const Family& a, const Family& b) { return a.share > b.share; });
  std::string d;
  for (size_t k = 0; k < families.size(); ++k) {
    if (static_cast<int>(k) >= options.max_dominant_states) break;
    if (k > 0 && families[k].share < options.dominant_share) break;
    d += (d.empty() ? "" : ", ") + families[k].name + " " + Percent(families[k].share);
    if (k == 0) m.whirl = families[k].whirl;
  }
  m.description = d;
}

}  // namespace

BladeCoordinates FindBladeCoordinates(const std::vector<LinChannel>& channels) {
  BladeCoordinates c;
  const int n = static_cast<int>(channels.size());
  c.group_of.assign(n, -1);
  c.blade_of.assign(n, -1);
  c.descriptions.resize(n);
  std::map<std::string, std::map<int, int>> groups;  // key → blade → channel
  std::vector<std::string> order;                    // keys in order of first appearance
  std::vector<std::string> stripped(n);
  std::vector<size_t> digit_at(n, std::string::npos);
  for (int i = 0; i < n; ++i) {
    stripped[i] = StripInternalIndex(channels[i].description);
    c.descriptions[i] = stripped[i];
    if (!channels[i].rotating_frame) continue;
    const auto at = BladeDigit(stripped[i]);
    if (!at)
      throw InputError("rotating-frame channel '" + channels[i].description +
                       "' names no blade number, so it cannot be grouped by blade");
    digit_at[i] = *at;
    const int blade = stripped[i][*at] - '0';
    std::string key = stripped[i];
    key[*at] = '#';
    if (!groups.count(key)) order.push_back(key);
    auto& members = groups[key];
    if (members.count(blade))
      throw InputError("rotating-frame channels '" + channels[members[blade]].description +
                       "' and '" + channels[i].description + "' are both blade " +
                       std::to_string(blade) + " of the same quantity");
    members[blade] = i;
  }
  int blades = 0;
  for (const auto& [key, members] : groups) blades = std::max(blades, members.rbegin()->first);
  for (const std::string& key : order) {
    const auto& members = groups[key];
    std::vector<int> group;
    for (int b = 1; b <= blades; ++b) {
      const auto it = members.find(b);
      if (it == members.end())
        throw InputError("rotating-frame channel '" +
                         channels[members.begin()->second].description +
                         "' has no counterpart on blade " + std::to_string(b) + " (" +
                         std::to_string(blades) + " blades found)");
      group.push_back(it->second);
    }
    if (members.begin()->first != 1)
      throw InputError("rotating-frame channel '" + channels[members.begin()->second].description +
                       "': blade numbers must start at 1");
    const int g = static_cast<int>(c.groups.size());
    for (int b = 0; b < blades; ++b) {
      const int i = group[b];
      c.group_of[i] = g;
      c.blade_of[i] = b;
      std::string d = stripped[i];
      std::string word = "(";  // built in steps: GCC 12 warns falsely on "(" + s + ")"
      word += CoordinateWord(blades, b);
      word += ')';
      d.replace(digit_at[i], 1, word);
      c.descriptions[i] = d;
    }
    c.groups.push_back(std::move(group));
  }
  c.blades = blades;
  return c;
}

std::vector<int> RateOf(const std::vector<LinChannel>& states) {
  const int n = static_cast<int>(states.size());
  std::vector<int> rate_of(n, -1);
  auto module = [&](int i) { return ModuleOf(states[static_cast<size_t>(i)]); };
  int start = 0;
  while (start < n) {
    int end = start + 1;
    while (end < n && module(end) == module(start) &&
           states[end].derivative_order == states[start].derivative_order)
      ++end;
    if (states[start].derivative_order == 2) {
      const int size = end - start;
      if (size % 2 != 0)
        throw InputError("the " + std::to_string(size) + " second-order states of module '" +
                         module(start) + "' from '" + states[start].description +
                         "' are not displacement/rate pairs (odd count)");
      for (int j = 0; j < size / 2; ++j) rate_of[start + size / 2 + j] = start + j;
    }
    start = end;
  }
  return rate_of;
}

MbcStateTransform MbcStateTransformAt(const BladeCoordinates& states,
                                      const std::vector<int>& rate_of, double psi, double omega,
                                      double omega_dot) {
  const int n = static_cast<int>(states.group_of.size());
  MbcStateTransform t{MatrixXd::Identity(n, n), MatrixXd::Zero(n, n)};
  if (states.groups.empty()) return t;
  const int N = states.blades;
  const MatrixXd t0 = MbcTransform(N, psi, 0), t1 = MbcTransform(N, psi, 1),
                 t2 = MbcTransform(N, psi, 2);
  for (const auto& g : states.groups) {
    const bool rates = rate_of[g[0]] >= 0;
    for (int b = 0; b < N; ++b) {
      t.T(g[b], g[b]) = 0;
      for (int c = 0; c < N; ++c) {
        t.T(g[b], g[c]) = t0(b, c);
        t.T_dot(g[b], g[c]) = omega * t1(b, c);
        if (rates) {  // q̇_b = Σ_c t̃_bc ż_c + Ω t̃'_bc z_c
          const int d = rate_of[g[c]];
          t.T(g[b], d) = omega * t1(b, c);
          t.T_dot(g[b], d) = omega * omega * t2(b, c) + omega_dot * t1(b, c);
        }
      }
    }
  }
  return t;
}

MatrixXd MbcChannelTransformAt(const BladeCoordinates& channels, double psi) {
  const int n = static_cast<int>(channels.group_of.size());
  MatrixXd t = MatrixXd::Identity(n, n);
  if (channels.groups.empty()) return t;
  const MatrixXd t0 = MbcTransform(channels.blades, psi, 0);
  for (const auto& g : channels.groups)
    for (int b = 0; b < channels.blades; ++b)
      for (int c = 0; c < channels.blades; ++c) t(g[b], g[c]) = t0(b, c);
  return t;
}

namespace {

// Inputs and outputs are transformed when their rotating channels form tuples of the states'
// blade count; otherwise B, C, D are left out of the result (the state analysis does not need
// them), and the diagnostics say why.
void FindChannelCoordinates(const LinOperatingPoint& op, bool* with_inputs, bool* with_outputs,
                            Mbc3Result& r) {
  const LtiSystem& s0 = op.samples.front();
  *with_inputs = s0.B.size() > 0 && static_cast<int>(op.inputs.size()) == s0.B.cols();
  *with_outputs = s0.C.size() > 0 && static_cast<int>(op.outputs.size()) == s0.C.rows();
  if (s0.B.size() > 0 && !*with_inputs)
    r.diagnostics.push_back({DiagnosticCode::kMbcNotTransformed, Severity::kNote,
                             "B not transformed: the files have no input table"});
  if (s0.C.size() > 0 && !*with_outputs)
    r.diagnostics.push_back({DiagnosticCode::kMbcNotTransformed, Severity::kNote,
                             "C not transformed: the files have no output table"});
  auto channels = [&](const std::vector<LinChannel>& list, bool* use, const char* what) {
    BladeCoordinates c;
    if (!*use) return c;
    try {
      c = FindBladeCoordinates(list);
      if (c.blades != 0 && c.blades != r.blades)
        throw InputError(std::string("rotating ") + what + " form tuples of " +
                         std::to_string(c.blades) + " blades, the states of " +
                         std::to_string(r.blades));
    } catch (const InputError& e) {
      r.diagnostics.push_back({DiagnosticCode::kMbcNotTransformed, Severity::kWarning,
                               std::string(what) + " not transformed (" + e.what() + ")"});
      *use = false;
      c = BladeCoordinates();
    }
    return c;
  };
  r.input_coordinates = channels(op.inputs, with_inputs, "inputs");
  r.output_coordinates = channels(op.outputs, with_outputs, "outputs");
}

// Every azimuth sample in multi-blade coordinates (Bir 2008, eq. 29), and their mean.
void TransformSamples(const LinOperatingPoint& op, const Mbc3Options& options,
                      const std::vector<int>& rate_of, bool with_inputs, bool with_outputs,
                      Mbc3Result& r) {
  const int K = op.size();
  LtiSystem& mean = r.average;
  auto add = [K](MatrixXd& sum, const MatrixXd& m) {
    if (m.size() == 0) return;
    if (sum.size() == 0) sum = MatrixXd::Zero(m.rows(), m.cols());
    sum += m / K;
  };
  for (int k = 0; k < K; ++k) {
    const double psi = op.azimuths[k];
    const double omega =
        options.speed_from_operating_point ? op.operating_speeds[k] : op.rotor_speeds[k];
    const double omega_dot =
        options.speed_from_operating_point ? op.operating_accelerations[k] : 0.0;
    const MbcStateTransform t =
        MbcStateTransformAt(r.state_coordinates, rate_of, psi, omega, omega_dot);
    const Eigen::PartialPivLU<MatrixXd> lu(t.T);
    const LtiSystem& s = op.samples[k];
    LtiSystem x;
    x.A = lu.solve(s.A * t.T - t.T_dot);  // Bir (2008) eq. 29
    if (with_inputs) x.B = lu.solve(s.B * MbcChannelTransformAt(r.input_coordinates, psi));
    if (with_outputs) {
      const Eigen::PartialPivLU<MatrixXd> out(MbcChannelTransformAt(r.output_coordinates, psi));
      x.C = out.solve(s.C * t.T);
      if (with_inputs && s.D.size() > 0)
        x.D = out.solve(s.D * MbcChannelTransformAt(r.input_coordinates, psi));
    }
    add(mean.A, x.A);
    add(mean.B, x.B);
    add(mean.C, x.C);
    add(mean.D, x.D);
    r.transformed.push_back(std::move(x));
  }
  const double norm = mean.A.norm();
  for (const LtiSystem& x : r.transformed)
    r.periodic_part = std::max(r.periodic_part, (x.A - mean.A).norm() / std::max(norm, 1e-300));
}

// One mode per eigenvalue of the averaged matrix with Im λ ≥ 0 (a conjugate is not listed
// twice), with the states that take part in it: participation per displacement (its rate's
// added) and first-order state.
bool ModesOfTheAverage(const std::vector<int>& rate_of, const Mbc3Options& options, Mbc3Result& r) {
  const Eigen::EigenSolver<MatrixXd> eig(r.average.A);
  if (eig.info() != Eigen::Success) {
    r.diagnostics.push_back({DiagnosticCode::kMbcEigenFailed, Severity::kFailure,
                             "the eigenvalue solver did not converge on the averaged matrix"});
    return false;
  }
  const int n = static_cast<int>(r.average.A.rows());
  const Eigen::VectorXcd values = eig.eigenvalues();
  const Eigen::MatrixXcd vectors = eig.eigenvectors();
  const Eigen::MatrixXcd left = LeftEigenvectors(vectors);  // empty for a defective matrix
  for (int k = 0; k < n; ++k) {
    const std::complex<double> lambda = values[k];
    if (lambda.imag() < 0) continue;
    MbcMode m;
    m.eigenvalue = lambda;
    const double magnitude = std::abs(lambda);
    m.natural_frequency_hz = magnitude / (2 * pi);
    m.damped_frequency_hz = lambda.imag() / (2 * pi);
    m.damping_ratio = magnitude > 0 ? -lambda.real() / magnitude : 0;
    m.kind = lambda.imag() > 0 ? MbcMode::Kind::kOscillatory : MbcMode::Kind::kReal;
    // Scaled so its largest entry is 1: phases then read against the state that leads.
    Eigen::Index lead = 0;
    vectors.col(k).cwiseAbs().maxCoeff(&lead);
    m.eigenvector = vectors.col(k) / vectors(lead, k);
    if (left.size())
      m.participation = vectors.col(k).cwiseProduct(left.row(k).transpose());
    else
      m.participation = Eigen::VectorXcd::Zero(n);
    const Eigen::VectorXcd p = ParticipationPerDisplacement(rate_of, m.participation);
    double total = 0;
    for (int i = 0; i < n; ++i)
      if (rate_of[i] < 0) total += std::abs(p[i]);
    std::vector<MbcMode::Share> shares;
    for (int i = 0; i < n; ++i)
      if (rate_of[i] < 0 && total > 0) shares.push_back({i, std::abs(p[i]) / total});
    std::sort(shares.begin(), shares.end(),
              [](const MbcMode::Share& a, const MbcMode::Share& b) { return a.share > b.share; });
    for (const auto& s : shares) {
      if (static_cast<int>(m.dominant.size()) >= options.max_dominant_states) break;
      if (s.share < options.dominant_share && !m.dominant.empty()) break;
      m.dominant.push_back(s);
    }
    r.modes.push_back(std::move(m));
  }
  return true;
}

// The rigid rotation: the real mode nearest 0 led by the azimuth state; or an exact zero.
void MarkRigidBodyModes(const LinOperatingPoint& op, Mbc3Result& r) {
  const double norm = r.average.A.norm();
  int rigid = -1;
  for (int k = 0; k < static_cast<int>(r.modes.size()); ++k) {
    const MbcMode& m = r.modes[k];
    if (m.kind != MbcMode::Kind::kReal || m.dominant.empty() || !op.azimuth_state ||
        m.dominant.front().state != *op.azimuth_state)
      continue;
    if (rigid < 0 || std::abs(m.eigenvalue) < std::abs(r.modes[rigid].eigenvalue)) rigid = k;
  }
  for (int k = 0; k < static_cast<int>(r.modes.size()); ++k) {
    MbcMode& m = r.modes[k];
    if (k == rigid || std::abs(m.eigenvalue) <= 1e-9 * std::max(norm, 1.0)) {
      m.rigid_body = true;
      m.kind = MbcMode::Kind::kRigidBody;
      ++r.rigid_body_modes;
    }
  }
}

}  // namespace

Mbc3Result Mbc3(const LinOperatingPoint& op, const Mbc3Options& options) {
  Mbc3Result r;
  r.rotor_speed = op.rotor_speed;
  r.azimuths = op.azimuths;
  r.state_coordinates = FindBladeCoordinates(op.states);
  r.blades = r.state_coordinates.blades;
  const int n = static_cast<int>(op.states.size());
  if (r.blades == 1 || r.blades == 2) {
    r.reason = "multi-blade coordinates need at least 3 blades; these files describe " +
               std::to_string(r.blades) +
               std::string(r.blades == 2 ? " (a two-bladed rotor has no cyclic pair, so its "
                                           "equations stay periodic in any blade-based "
                                           "coordinates)"
                                         : "") +
               ": use the Floquet analysis";
    return r;
  }
  r.applicable = true;
  const std::vector<int> rate_of = RateOf(op.states);
  CheckRateGroups(r.state_coordinates, rate_of, op.states);
  if (r.blades == 0)
    r.diagnostics.push_back({DiagnosticCode::kNoRotatingStates, Severity::kNote,
                             "no rotating-frame states: the transform is the identity"});
  bool with_inputs = false, with_outputs = false;
  FindChannelCoordinates(op, &with_inputs, &with_outputs, r);
  r.states = op.states;
  for (int i = 0; i < n; ++i) {
    r.states[i].description = r.state_coordinates.descriptions[i];
    r.states[i].rotating_frame = false;
  }
  TransformSamples(op, options, rate_of, with_inputs, with_outputs, r);
  if (!ModesOfTheAverage(rate_of, options, r)) return r;
  MarkRigidBodyModes(op, r);
  std::stable_sort(r.modes.begin(), r.modes.end(), [](const MbcMode& a, const MbcMode& b) {
    if (a.natural_frequency_hz != b.natural_frequency_hz)
      return a.natural_frequency_hz < b.natural_frequency_hz;
    return a.damped_frequency_hz < b.damped_frequency_hz;
  });
  r.max_real_part = -std::numeric_limits<double>::infinity();
  for (MbcMode& m : r.modes) {
    DescribeMode(r.state_coordinates, rate_of, r.states, options, m);
    if (!m.rigid_body) r.max_real_part = std::max(r.max_real_part, m.eigenvalue.real());
  }
  for (const MbcMode& m : r.modes)
    if (m.rigid_body) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "rigid-body mode λ = %.3g 1/s: the rotor's rigid rotation, exactly 0 for the "
                    "periodic system; its distance from 0 is the error of sampling and averaging",
                    m.eigenvalue.real());
      r.diagnostics.push_back({DiagnosticCode::kRigidBodyMode, Severity::kNote, buf});
    }
  return r;
}

LinOperatingPoint InMultiBladeCoordinates(const LinOperatingPoint& op, const Mbc3Result& mbc) {
  if (!mbc.applicable) throw InputError(mbc.reason);
  LinOperatingPoint out = op;
  out.states = mbc.states;
  out.samples = mbc.transformed;
  const LtiSystem& s0 = mbc.transformed.front();
  if (s0.B.size() == 0)
    out.inputs.clear();
  else
    for (size_t i = 0; i < out.inputs.size(); ++i) {
      out.inputs[i].description = mbc.input_coordinates.descriptions[i];
      out.inputs[i].rotating_frame = false;
    }
  if (s0.C.size() == 0)
    out.outputs.clear();
  else
    for (size_t i = 0; i < out.outputs.size(); ++i) {
      out.outputs[i].description = mbc.output_coordinates.descriptions[i];
      out.outputs[i].rotating_frame = false;
    }
  out.diagnostics.push_back(
      {DiagnosticCode::kMultiBladeCoordinates, Severity::kNote,
       mbc.blades > 0
           ? "in multi-blade coordinates (" + std::to_string(mbc.blades) +
                 " blades): the transformed matrices at each azimuth, not averaged"
           : std::string("no rotating-frame blade states: the multi-blade transform is the "
                         "identity and the files' coordinates are used as they are")});
  return out;
}

PeriodicSystem TransformedMultiBlade(const PeriodicSystem& system, const LinOperatingPoint& op,
                                     const Mbc3Result& mbc, bool to_multiblade,
                                     bool channels_only) {
  if (!mbc.applicable) throw InputError("multi-blade coordinates do not apply to this model");
  const BladeCoordinates states = mbc.state_coordinates;
  const std::vector<int> rate_of = RateOf(op.states);
  const double omega = op.rotor_speed;
  const int n = system.states();
  // T(ψ) is the identity but on the blade groups' 3 × 3 (N × N) blocks: sparse, so a sample
  // costs O(n²) products and a sparse LU, not three dense n³ ones (250 states: a dense sample
  // was about 10 ms, and the fit takes dozens).
  const PeriodicSystem::MatrixFunction a = [=](double t, Eigen::Ref<MatrixXd> out) {
    if (channels_only) {
      out = system.A(t);
      return;
    }
    const MbcStateTransform x = MbcStateTransformAt(states, rate_of, omega * t, omega, 0);
    const Eigen::SparseMatrix<double> t_sparse = x.T.sparseView(), t_dot = x.T_dot.sparseView();
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(t_sparse);
    if (lu.info() != Eigen::Success)
      throw InputError("the multi-blade transform is singular at azimuth " +
                       MessageNumber(omega * t) + " rad");
    const MatrixXd given = system.A(t);
    if (to_multiblade) {
      out = lu.solve(MatrixXd(given * t_sparse - t_dot));
    } else {
      const Eigen::SparseMatrix<double> t_inverse =
          MatrixXd(lu.solve(MatrixXd::Identity(n, n))).sparseView();
      out = (t_sparse * given + t_dot) * t_inverse;
    }
  };
  // Inputs and outputs as the analysed model has them: u_R = T_u u_NR, y_NR = T_y⁻¹ y_R, so that
  // its partial FRFs compare channel by channel (identity transforms for untransformed tables).
  const BladeCoordinates inputs = mbc.input_coordinates, outputs = mbc.output_coordinates;
  const int m = system.inputs(), p = system.outputs();
  auto channel = [](const BladeCoordinates& c, int size, double psi, bool inverse) {
    if (static_cast<int>(c.group_of.size()) != size)
      return MatrixXd(MatrixXd::Identity(size, size));
    const MatrixXd t_c = MbcChannelTransformAt(c, psi);
    return inverse ? MatrixXd(t_c.inverse()) : t_c;
  };
  const bool to = to_multiblade;
  const PeriodicSystem::MatrixFunction b_of = [=](double t, Eigen::Ref<MatrixXd> out) {
    const MatrixXd given = system.B(t) * channel(inputs, m, omega * t, !to);
    if (channels_only) {
      out = given;
      return;
    }
    const MbcStateTransform x = MbcStateTransformAt(states, rate_of, omega * t, omega, 0);
    out = to ? MatrixXd(x.T.partialPivLu().solve(given)) : MatrixXd(x.T * given);
  };
  const PeriodicSystem::MatrixFunction c_of = [=](double t, Eigen::Ref<MatrixXd> out) {
    const MatrixXd given = channel(outputs, p, omega * t, to) * system.C(t);
    if (channels_only) {
      out = given;
      return;
    }
    const MbcStateTransform x = MbcStateTransformAt(states, rate_of, omega * t, omega, 0);
    out = to ? MatrixXd(given * x.T) : MatrixXd(given * x.T.partialPivLu().inverse());
  };
  const PeriodicSystem::MatrixFunction d_of = [=](double t, Eigen::Ref<MatrixXd> out) {
    out = channel(outputs, p, omega * t, to) * system.D(t) * channel(inputs, m, omega * t, !to);
  };
  FourierFitOptions fit;
  fit.tol = 1e-14;
  fit.max_samples = 256;  // harmonics of ψ up to those of A plus two: a few dozen at most
  auto fitted = [&](const PeriodicSystem::MatrixFunction& matrix, int rows, int cols) {
    if (rows == 0 || cols == 0) return FourierMatrix();
    const FourierFit f = FitFourier(matrix, rows, cols, system.period(), fit);
    if (!f.converged)
      throw InputError("the model in the other coordinates is not a finite Fourier series");
    return f.series;
  };
  return PeriodicSystem::FromFourier(system.period(), fitted(a, n, n), fitted(b_of, n, m),
                                     fitted(c_of, p, n), fitted(d_of, p, m))
      .WithLabels(system.labels())
      .WithRotorSpeed(omega);
}

}  // namespace ltp
