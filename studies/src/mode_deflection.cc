#include "ltp/studies/mode_deflection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ltp/core/error.h"

namespace ltp {
namespace {

// The largest distance between two rest nodes: the structure's size.
double Size(const StructureGeometry& g) {
  double size = 0;
  for (const DrawnBody& a : g.bodies)
    for (const DrawnBody& b : g.bodies)
      for (int i = 0; i < a.rest.cols(); ++i)
        size = std::max(size, (b.rest.colwise() - a.rest.col(i)).colwise().norm().maxCoeff());
  return size;
}

// Node displacements of `body` for displacement coordinates q (3 × nodes).
Eigen::Matrix3Xd Displacement(const DrawnBody& body, const Eigen::VectorXd& q) {
  const Eigen::VectorXd d = body.motion * q;
  return Eigen::Map<const Eigen::Matrix3Xd>(d.data(), 3, body.rest.cols());
}

}  // namespace

void ModeDeflectionOptions::Validate() const {
  const OptionCheck check("ModeDeflectionOptions");
  if (!(amplitude > 0 && amplitude <= 1))
    check.Fail("amplitude", amplitude, "0 < amplitude <= 1 (a fraction of the structure's size)");
}

ModeDeflections DeflectModes(const GeometryAt& geometry, const FloquetResult& floquet,
                             const std::vector<int>& modes, const ModeDeflectionOptions& options) {
  options.Validate();
  if (floquet.mode_samples.empty())
    throw InputError("no periodic mode shapes to draw: the Floquet analysis computed none");
  const int count = static_cast<int>(floquet.modes.size());
  std::vector<int> chosen = modes;
  if (chosen.empty())
    for (int k = 0; k < count; ++k) chosen.push_back(k);
  for (int k : chosen)
    if (k < 0 || k >= count)
      throw InputError("there is no mode " + std::to_string(k + 1) + " (index " +
                       std::to_string(k) + "): the analysis has " + std::to_string(count) +
                       (count == 1 ? " mode" : " modes"));
  // The geometry at each sample time, computed once for every mode.
  std::vector<StructureGeometry> at;
  for (double t : floquet.sample_times) at.push_back(geometry(t));
  if (at.front().bodies.empty()) throw InputError("the structure has no bodies to draw");
  const Eigen::Index dofs = at.front().bodies.front().motion.cols();
  for (const StructureGeometry& g : at)
    for (const DrawnBody& b : g.bodies)
      if (b.motion.cols() != dofs || b.motion.rows() != 3 * b.rest.cols())
        throw InputError("the drawn body '" + b.name + "' does not match the structure's " +
                         std::to_string(dofs) + " coordinates");
  if (floquet.mode_samples.front().rows() < dofs)
    throw InputError("the structure has " + std::to_string(dofs) +
                     " coordinates but the analysed system only " +
                     std::to_string(floquet.mode_samples.front().rows()) + " states");
  ModeDeflections out;
  out.axes = at.front().axes;
  for (const DrawnBody& b : at.front().bodies) out.bodies.push_back(b.name);
  const double size = Size(at.front());

  for (int k : chosen) {
    ModeDeflection m;
    m.mode = k;
    m.exponent = floquet.modes[static_cast<size_t>(k)].exponent;
    if (static_cast<size_t>(k) < floquet.mode_descriptions.size())
      m.description = floquet.mode_descriptions[static_cast<size_t>(k)];
    // Re(e^{λt} ξ_q(t)): the mode's own free motion (branch-independent), decay included.
    std::vector<Eigen::VectorXd> q;
    for (size_t s = 0; s < floquet.sample_times.size(); ++s)
      q.push_back((std::exp(m.exponent * floquet.sample_times[s]) *
                   floquet.mode_samples[s].col(k).head(dofs))
                      .real());
    double largest = 0;
    for (size_t s = 0; s < q.size(); ++s)
      for (const DrawnBody& b : at[s].bodies)
        largest = std::max(largest, Displacement(b, q[s]).colwise().norm().maxCoeff());
    // A mode that does not move the drawn structure (e.g. a rate-only state) stays at rest.
    m.scale = largest > 0 ? options.amplitude * size / largest : 0;
    for (size_t s = 0; s < q.size(); ++s) {
      DeflectionFrame f;
      f.t = floquet.sample_times[s];
      for (size_t i = 0; i < at[s].bodies.size(); ++i) {
        const DrawnBody& b = at[s].bodies[i];
        const DrawnBody& standing = at.front().bodies[i];
        f.rest.push_back(b.rest);
        f.moved.push_back(b.rest + m.scale * Displacement(b, q[s]));
        f.standing.push_back(standing.rest + m.scale * Displacement(standing, q[s]));
      }
      m.frames.push_back(std::move(f));
    }
    out.modes.push_back(std::move(m));
  }
  return out;
}

}  // namespace ltp
