#pragma once
// Internal: arrays from numpy's .npz archives (np.savez, np.savez_compressed), the other form
// finite-element matrices come in from Python. A .npz file is a zip archive of .npy members;
// libzip reads the archive, the .npy header (a Python dict literal: descr, fortran_order,
// shape) is parsed here. Little-endian float64, float32, int64 and int32; 1-D arrays are columns.
#include <Eigen/Dense>
#include <string>

namespace ltp::internal {

/// Array `name` (the member name.npy) of the archive `path`, dense, at most
/// kMatrixMarketMaxSize rows and columns. @throws SceneError "path: name: what is wrong" on an
/// archive that cannot be read, a missing member (listing those present), another dtype, a
/// shape of more than 2 dimensions, a size beyond the limit, data of the wrong length or a
/// non-finite value.
Eigen::MatrixXd ReadNpzArray(const std::string& path, const std::string& name);

}  // namespace ltp::internal
