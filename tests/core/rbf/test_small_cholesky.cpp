// The local fits' in-place Cholesky factorisation against Eigen's LLT: the same factor up to
// rounding on both sides of the unblocked/blocked switch, the same solve, condition estimate and
// 1-norm, the strict upper triangle untouched, and failure on a matrix that is not definite.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Cholesky>

#include "core/rbf/small_cholesky.h"

using namespace hermite;

namespace {

// G Gᵀ + n I: symmetric positive definite, condition number below about 10.
Eigen::MatrixXd spdMatrix(Eigen::Index n, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return g(rng); });
  return G * G.transpose() + double(n) * Eigen::MatrixXd::Identity(n, n);
}

}  // namespace

TEST_CASE("SmallCholesky's factor, solve and condition estimate equal Eigen's LLT below and above the block switch") {
  std::mt19937 rng(23);
  for (const Eigen::Index n : {Eigen::Index(1), Eigen::Index(5), Eigen::Index(40), kSmallCholeskyUnblockedUpTo,
                               kSmallCholeskyUnblockedUpTo + 1, Eigen::Index(150), Eigen::Index(257)}) {
    CAPTURE(n);
    const Eigen::MatrixXd A = spdMatrix(n, rng);
    const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(n, [&] { return std::normal_distribution<double>()(rng); });
    const Eigen::LLT<Eigen::MatrixXd> llt(A);
    REQUIRE(llt.info() == Eigen::Success);
    // A inside a larger block whose strict upper triangle holds NaN: neither read nor written.
    Eigen::MatrixXd M = Eigen::MatrixXd::Constant(n + 4, n + 4, std::numeric_limits<double>::quiet_NaN());
    M.topLeftCorner(n, n).triangularView<Eigen::Lower>() = A;
    const SmallCholesky chol(M.topLeftCorner(n, n));
    REQUIRE(chol.ok());
    const Eigen::MatrixXd L = M.topLeftCorner(n, n).triangularView<Eigen::Lower>();
    const Eigen::MatrixXd Lref = llt.matrixL();
    CHECK((L - Lref).cwiseAbs().maxCoeff() <= 1e-13 * Lref.cwiseAbs().maxCoeff());
    CHECK(M.topLeftCorner(n, n).triangularView<Eigen::StrictlyUpper>().toDenseMatrix().array().isNaN().count() ==
          n * (n - 1) / 2);
    const Eigen::VectorXd x = chol.solve(b), xref = llt.solve(b);
    CHECK((x - xref).norm() <= 1e-12 * xref.norm());
    CHECK((A * x - b).norm() <= 1e-12 * b.norm());
    CHECK(std::abs(chol.rcond() / llt.rcond() - 1) <= 1e-6);
  }
}

TEST_CASE("SmallCholesky reports a matrix that is not positive definite") {
  std::mt19937 rng(29);
  for (const Eigen::Index n : {Eigen::Index(3), Eigen::Index(60), Eigen::Index(130)}) {
    CAPTURE(n);
    Eigen::MatrixXd A = spdMatrix(n, rng);
    A(n - 1, n - 1) = -1e6;  // the last pivot is negative
    CHECK_FALSE(SmallCholesky(A).ok());
    A = spdMatrix(n, rng);
    A(n / 2, n / 2) = -1e6;  // a pivot inside the first or a later block
    CHECK_FALSE(SmallCholesky(A).ok());
  }
}
