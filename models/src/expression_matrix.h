#pragma once
// Internal: matrices whose entries are expressions in t, compiled into the thread-safe
// MatrixFunctions of a PeriodicSystem. Entries that do not depend on t are evaluated once here;
// the others are evaluated per call with each thread's own parsers (TimeExpressionPool).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "expression.h"
#include "ltp/core/periodic_system.h"

namespace ltp::internal {

struct ExpressionEntry {
  std::string text;
  std::string where;  ///< prefix for error messages, e.g. "scene.yaml:6: state_space.A[1][0]"
};
/// Row-major entries; every row has the same length.
using ExpressionMatrixText = std::vector<std::vector<ExpressionEntry>>;

class ExpressionMatrices {
 public:
  /// `constants`: the parameter values; `period`: T, for the checks and the jump search.
  ExpressionMatrices(Constants constants, double period);

  /// Compiles a matrix, checks every entry is finite at t = 0, T/3 and 2T/3 and searches the
  /// entries that may jump for their jump times. Returns the matrix's handle.
  /// @throws SceneError naming the entry.
  int Add(const ExpressionMatrixText& text);

  /// The matrix `handle` when none of its entries depends on t, else empty. Before Finish.
  std::optional<Eigen::MatrixXd> ConstantValue(int handle) const;

  /// Jump times in [0, T) found so far (unsorted, may repeat).
  const std::vector<double>& jumps() const { return jumps_; }

  /// Functions for all added matrices, in handle order. Call once, after the last Add.
  std::vector<PeriodicSystem::MatrixFunction> Finish();

 private:
  struct Varying {
    int row, col, index;  // index into the pool's expressions
  };
  struct Compiled {
    Eigen::MatrixXd constant;      // t-independent entries; 0 where the entry varies
    std::vector<Varying> varying;  // t-dependent entries
  };
  struct Shared {
    std::vector<Compiled> matrices;
    std::unique_ptr<TimeExpressionPool> pool;
  };

  Constants constants_;
  double period_;
  std::vector<Compiled> matrices_;
  std::vector<std::string> varying_texts_;
  std::vector<double> jumps_;
};

}  // namespace ltp::internal
