// The one-pass symmetric 1-norm against LAPACK's dlansy, and its finiteness check.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include <lapacke.h>

#include "core/rbf/symmetric_norm.h"

using namespace hermite;

TEST_CASE("the one-pass symmetric 1-norm equals dlansy on blocks of any size and leading dimension") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Sizes below and above the threaded pass's threshold (256), inside a larger matrix.
  for (const Eigen::Index k : {Eigen::Index(1), Eigen::Index(2), Eigen::Index(7), Eigen::Index(255),
                               Eigen::Index(256), Eigen::Index(601)}) {
    CAPTURE(k);
    const Eigen::Index ld = k + 5;
    Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr(ld, ld, [&] { return u(rng); });
    const double expected = LAPACKE_dlansy(LAPACK_COL_MAJOR, '1', 'L', int(k), M.data(), int(ld));
    if (k > 1) M(0, k - 1) = std::numeric_limits<double>::quiet_NaN();  // the strict upper triangle is not read
    M(k, 0) = std::numeric_limits<double>::infinity();                   // nor the rows below the block
    const double norm = lowerSymmetricOneNorm(M.data(), k, ld);
    CHECK(std::abs(norm - expected) <= 1e-13 * expected);
  }
}

TEST_CASE("the one-pass symmetric 1-norm is NaN when an entry of the lower triangle is not finite") {
  const Eigen::Index k = 300;
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
    for (const auto& [i, j] : {std::pair<Eigen::Index, Eigen::Index>{0, 0}, {k - 1, 0}, {k - 1, k - 1}, {200, 150}}) {
      CAPTURE(bad);
      CAPTURE(i);
      CAPTURE(j);
      Eigen::MatrixXd M = Eigen::MatrixXd::Identity(k, k);
      M(i, j) = bad;
      CHECK(std::isnan(lowerSymmetricOneNorm(M.data(), k, k)));
    }
  }
  CHECK(lowerSymmetricOneNorm(nullptr, 0, 0) == 0);
}
