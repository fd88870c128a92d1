// MultiplyInto (ltp/integrate/detail/matrix_product.h) against Eigen's own
// product, below and above the size from which it calls BLAS, with out accumulated, and on row
// blocks (the lower half of A(t) in second-order form), whose leading dimension is not their row
// count.
#include "ltp/integrate/detail/matrix_product.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace ltp::internal {
namespace {

TEST(MatrixProduct, EqualsEigensProductOnEverySize) {
  for (int n : {2, kBlasColumns - 1, kBlasColumns, 60}) {
    SCOPED_TRACE(testing::Message() << "n = " << n);
    const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
    Eigen::MatrixXd out(n, n);
    MultiplyInto(a, b, out);
    const Eigen::MatrixXd want = a * b;
    EXPECT_LT((out - want).cwiseAbs().maxCoeff(), 1e-13 * n);

    // Lower half of a times b into the lower half of c (outer stride n on both sides).
    Eigen::MatrixXd c = Eigen::MatrixXd::Constant(n, n, 7.0);
    const int h = n / 2;
    MultiplyInto(a.bottomRows(n - h), b, c.bottomRows(n - h));
    EXPECT_LT((c.bottomRows(n - h) - a.bottomRows(n - h) * b).cwiseAbs().maxCoeff(), 1e-13 * n);
    EXPECT_TRUE((c.topRows(h).array() == 7.0).all()) << "rows outside the block were written";

    // Accumulated: c += a · b (beta = 1), and a tall product with two columns (the Taylor
    // stepper's weighted sums of its terms: BLAS by its work, not its column count).
    Eigen::MatrixXd d = Eigen::MatrixXd::Constant(n, n, 0.5);
    MultiplyInto(a, b, d, 1.0);
    EXPECT_LT((d - (want.array() + 0.5).matrix()).cwiseAbs().maxCoeff(), 1e-13 * n);
    const Eigen::MatrixXd tall = Eigen::MatrixXd::Random(n * n, 7),
                          two = Eigen::MatrixXd::Random(7, 2);
    Eigen::MatrixXd sums = Eigen::MatrixXd::Constant(n * n, 2, 3.0);
    MultiplyInto(tall, two, sums, 2.0);
    EXPECT_LT((sums - (tall * two).array().matrix() - Eigen::MatrixXd::Constant(n * n, 2, 6.0))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-13 * n);

    // Complex (zgemm), n × n times n × (n + 3).
    const Eigen::MatrixXcd p = Eigen::MatrixXcd::Random(n, n),
                           q = Eigen::MatrixXcd::Random(n, n + 3);
    Eigen::MatrixXcd pq(n, n + 3);
    MultiplyInto(p, q, pq);
    const Eigen::MatrixXcd want_pq = p * q;
    EXPECT_LT((pq - want_pq).cwiseAbs().maxCoeff(), 1e-13 * n);
  }
}

}  // namespace
}  // namespace ltp::internal
