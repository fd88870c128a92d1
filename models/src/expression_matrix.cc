#include "expression_matrix.h"

#include <cmath>
#include <optional>

#include "find_jumps.h"
#include "ltp/core/error.h"

namespace ltp::internal {
namespace {

[[noreturn]] void Fail(const ExpressionEntry& entry, const std::string& message) {
  throw SceneError(entry.where + ": " + message);
}

void CheckFinite(const ExpressionEntry& entry, double value, double t, bool depends_on_t) {
  if (std::isfinite(value)) return;
  std::string message = "'" + entry.text + "' evaluates to " + FormatValue(value);
  if (depends_on_t) message += " at t = " + FormatValue(t);
  Fail(entry, message);
}

}  // namespace

ExpressionMatrices::ExpressionMatrices(Constants constants, double period)
    : constants_(std::move(constants)), period_(period) {}

int ExpressionMatrices::Add(const ExpressionMatrixText& text) {
  const int rows = static_cast<int>(text.size());
  const int cols = rows > 0 ? static_cast<int>(text[0].size()) : 0;
  Compiled compiled{Eigen::MatrixXd::Zero(rows, cols), {}};
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const ExpressionEntry& entry = text[r][c];
      if (const std::optional<double> value = PlainNumber(entry.text)) {
        compiled.constant(r, c) = *value;
        CheckFinite(entry, *value, 0, false);
        continue;
      }
      std::optional<TimeExpression> expression;
      try {
        expression.emplace(entry.text, constants_);
      } catch (const ExpressionError& e) {
        Fail(entry, e.what());
      }
      if (!expression->depends_on_t()) {
        compiled.constant(r, c) = (*expression)(0);
        CheckFinite(entry, compiled.constant(r, c), 0, false);
        continue;
      }
      for (double t : {0.0, period_ / 3, 2 * period_ / 3})
        CheckFinite(entry, (*expression)(t), t, true);
      if (expression->may_jump()) {
        constexpr int kGrid = 4096;
        const auto found = FindJumps([&](double t) { return (*expression)(t); }, period_, kGrid);
        // Jumps in a quarter of the scan's steps: the scan does not resolve them (sign(sin(1e9 t))
        // jumps 3e5 times per step), and an integrator restarted at each would not finish.
        if (found.size() > kGrid / 4)
          Fail(entry, "jumps at least " + std::to_string(found.size()) + " times per period (in " +
                          std::to_string(found.size()) + " of the " + std::to_string(kGrid) +
                          " steps the period was scanned in): more jumps than can be located "
                          "and integrated between; check the expression's time scale");
        jumps_.insert(jumps_.end(), found.begin(), found.end());
      }
      compiled.varying.push_back({r, c, static_cast<int>(varying_texts_.size())});
      varying_texts_.push_back(entry.text);
    }
  }
  matrices_.push_back(std::move(compiled));
  return static_cast<int>(matrices_.size()) - 1;
}

std::optional<Eigen::MatrixXd> ExpressionMatrices::ConstantValue(int handle) const {
  const Compiled& m = matrices_.at(static_cast<size_t>(handle));
  if (!m.varying.empty()) return std::nullopt;
  return m.constant;
}

std::vector<PeriodicSystem::MatrixFunction> ExpressionMatrices::Finish() {
  auto shared = std::make_shared<Shared>();
  shared->matrices = std::move(matrices_);
  shared->pool = std::make_unique<TimeExpressionPool>(std::move(varying_texts_), constants_);
  std::vector<PeriodicSystem::MatrixFunction> functions;
  for (size_t k = 0; k < shared->matrices.size(); ++k) {
    functions.push_back([shared = std::shared_ptr<const Shared>(shared), k](
                            double t, Eigen::Ref<Eigen::MatrixXd> out) {
      const Compiled& m = shared->matrices[k];
      out = m.constant;
      if (m.varying.empty()) return;
      TimeExpressionPool::Evaluator& evaluator = shared->pool->ForThisThread();
      evaluator.SetTime(t);
      for (const Varying& v : m.varying) out(v.row, v.col) = evaluator.Value(v.index);
    });
  }
  return functions;
}

}  // namespace ltp::internal
