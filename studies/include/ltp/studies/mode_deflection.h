#pragma once
// A Floquet mode's deflected shape over one period, for animation: the free motion
// x(t) = Re(e^{λt} ξ(t)) of the mode, its displacement coordinates carried to the nodes of the
// scene's drawn structure (ltp/models/structure_geometry.h) at the mode's sample times. The
// rest positions turn with the rotor; the deflection is scaled so that the largest node
// displacement over the period is `amplitude` times the structure's size.
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "ltp/floquet/floquet.h"
#include "ltp/models/structure_geometry.h"

namespace ltp {

struct ModeDeflectionOptions {
  /// Largest node displacement over the period as a fraction of the structure's size (the
  /// largest distance between two nodes at rest at t = 0). Exaggerated for the eye: the
  /// linear model's deflections have no size of their own.
  double amplitude = 0.1;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// The structure at one sample time.
struct DeflectionFrame {
  double t = 0;                         ///< s, in [0, T)
  std::vector<Eigen::Matrix3Xd> rest;   ///< per body: node positions at rest (m)
  std::vector<Eigen::Matrix3Xd> moved;  ///< per body: rest + scale · Re(e^{λt} ξ_q(t)) mapped
  /// Per body: the same coordinates drawn on the structure as it stands at t = 0 (rest and
  /// motion per coordinate of t = 0): the blades stand still and show their own flap and lag,
  /// and the bodies stay joined — what a mode-shape plot shows.
  std::vector<Eigen::Matrix3Xd> standing;
};

struct ModeDeflection {
  int mode = 0;                   ///< index into FloquetResult::modes (0-based)
  std::complex<double> exponent;  ///< λ (1/s), on the mode's branch
  std::string description;        ///< the mode's description (FloquetResult::mode_descriptions)
  double scale = 0;               ///< the factor on Re(e^{λt} ξ_q(t)) (m per unit coordinate)
  std::vector<DeflectionFrame> frames;
};

struct ModeDeflections {
  std::string axes;                 ///< what x, y, z mean (StructureGeometry::axes)
  std::vector<std::string> bodies;  ///< names, in the frames' order
  std::vector<ModeDeflection> modes;
};

/// Every mode of `floquet` (or those listed in `modes`, 0-based) over one period, at the
/// result's mode sample times. The geometry's motion columns are the generalized coordinates,
/// the first states of the analysed system. @throws InputError when the result has no mode
/// shapes, the bodies disagree on the coordinates or have more than the system has states, or
/// a listed mode does not exist.
ModeDeflections DeflectModes(const GeometryAt& geometry, const FloquetResult& floquet,
                             const std::vector<int>& modes = {},
                             const ModeDeflectionOptions& options = {});

}  // namespace ltp
