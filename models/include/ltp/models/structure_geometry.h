#pragma once
// What a structural scene draws of itself: the nodes of its beams in space at a time t, at
// rest and per generalized coordinate. A mode's deflected shape over a period
// (ltp/studies/mode_deflection.h) moves these nodes by the mode's displacement coordinates.
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace ltp {

/// One drawn polyline: a beam (or a rigid link) as a chain of nodes.
struct DrawnBody {
  std::string name;       ///< "cantilever", "blade1", ...
  Eigen::Matrix3Xd rest;  ///< node positions (m) of the undeformed structure at t, one column each
  /// 3·nodes × dofs: node j's displacement (rows 3j..3j+2: x, y, z) per unit of each
  /// generalized coordinate, to first order (the linearisation the scene's equations use).
  Eigen::MatrixXd motion;
};

/// The structure at one time: its drawn bodies and the inertial axes they are given in.
struct StructureGeometry {
  std::string axes;  ///< what x, y and z mean, one line
  std::vector<DrawnBody> bodies;
};

/// A scene's structure at time t (s); the generalized coordinates are the first `dofs` states
/// of its second-order system.
using GeometryAt = std::function<StructureGeometry(double t)>;

}  // namespace ltp
