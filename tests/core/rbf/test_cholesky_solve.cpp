// The panelled solve with a Cholesky factor against LAPACK's dpotrs.

#include <doctest/doctest.h>

#include <random>

#include <lapacke.h>

#include "core/rbf/cholesky_solve.h"

using namespace hermite;

TEST_CASE("the panelled Cholesky solve agrees with dpotrs on blocks of any size and leading dimension") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Sizes below, at and across the 128-column panels; the block sits inside a larger matrix.
  for (const Eigen::Index k : {Eigen::Index(1), Eigen::Index(5), Eigen::Index(128), Eigen::Index(129),
                               Eigen::Index(300), Eigen::Index(517)}) {
    CAPTURE(k);
    const Eigen::Index ld = k + 3;
    Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr(ld, ld, [&] { return u(rng); });
    Eigen::MatrixXd S = M.topLeftCorner(k, k) * M.topLeftCorner(k, k).transpose();
    S.diagonal().array() += 1.0;  // symmetric positive definite, condition about 10³
    M.topLeftCorner(k, k) = S;
    if (k > 1) M(0, k - 1) = 1e300;  // the strict upper triangle is not read
    REQUIRE(LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', int(k), M.data(), int(ld)) == 0);
    const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(k, [&] { return u(rng); });
    Eigen::VectorXd expected = b;
    REQUIRE(LAPACKE_dpotrs(LAPACK_COL_MAJOR, 'L', int(k), 1, M.data(), int(ld), expected.data(), int(k)) == 0);
    Eigen::VectorXd x = b;
    solveWithCholeskyFactor(M.data(), k, ld, x);
    CHECK((x - expected).cwiseAbs().maxCoeff() <= 1e-11 * expected.cwiseAbs().maxCoeff());
    CHECK((S * x - b).cwiseAbs().maxCoeff() <= 1e-10 * b.cwiseAbs().maxCoeff() * S.cwiseAbs().maxCoeff());
  }
}
