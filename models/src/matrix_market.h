#pragma once
// Internal: a strict reader of Matrix Market files (.mtx), the text format finite-element
// packages and scipy.io.mmwrite write matrices in. Real and integer fields, coordinate and array
// formats, general, symmetric and skew-symmetric storage. Eigen's unsupported loadMarket is not
// used: it ignores the symmetry line (a symmetric file, scipy's default for a symmetric matrix,
// would give its lower triangle only), prints to stderr and skips bad entries.
#include <Eigen/Dense>
#include <string>

namespace ltp::internal {

/// Largest number of rows or columns accepted (a dense matrix of that size is 128 MB).
inline constexpr int kMatrixMarketMaxSize = 4096;

/// Refuses, before anything is read, what a matrix reader must not open: a path that is not a
/// regular file (a scene naming /dev/zero or a FIFO must not hang the reader) or one larger
/// than 1 GiB. `what` names the expected file in the message ("Matrix Market file").
/// @throws SceneError "path: ...".
void CheckMatrixFile(const std::string& path, const std::string& what);

/// The matrix in `path`, dense. @throws SceneError "path:line: what is wrong" on a file that
/// cannot be read, a header other than "%%MatrixMarket matrix coordinate|array real|integer
/// general|symmetric|skew-symmetric", a size beyond kMatrixMarketMaxSize, an entry outside the
/// matrix or in the wrong triangle, a repeated entry, a non-finite value, or a count that
/// differs from the size line's.
Eigen::MatrixXd ReadMatrixMarket(const std::string& path);

}  // namespace ltp::internal
