// The local fits' Cholesky condition estimate against Eigen's LLT::rcond(), LAPACK's dpocon and
// the true ‖A⁻¹‖₁, on random symmetric positive definite matrices of the local fits' sizes.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <lapacke.h>

#include "core/rbf/cholesky_condition.h"

using namespace hermite;

namespace {

// A = Q diag(λ) Qᵀ with Q a random orthogonal matrix and λ log-spaced from 1 down to 1/κ.
Eigen::MatrixXd randomSpd(Eigen::Index n, double kappa, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return g(rng); });
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(G).householderQ();
  Eigen::VectorXd lambda(n);
  for (Eigen::Index i = 0; i < n; ++i) lambda(i) = std::pow(kappa, -double(i) / double(n - 1));
  const Eigen::MatrixXd A = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (A + A.transpose());
}

double trueInverseOneNorm(const Eigen::MatrixXd& A) {
  return A.llt().solve(Eigen::MatrixXd::Identity(A.rows(), A.cols())).cwiseAbs().colwise().sum().maxCoeff();
}

}  // namespace

TEST_CASE("the Cholesky condition estimate equals Eigen's rcond and bounds like dpocon on random SPD matrices") {
  std::mt19937 rng(17);
  for (const Eigen::Index n : {Eigen::Index(20), Eigen::Index(33), Eigen::Index(64), Eigen::Index(120),
                               Eigen::Index(200)}) {
    for (const double kappa : {1e1, 1e4, 1e8, 1e11}) {
      CAPTURE(n);
      CAPTURE(kappa);
      const Eigen::MatrixXd A = randomSpd(n, kappa, rng);
      const Eigen::LLT<Eigen::MatrixXd> llt(A);
      REQUIRE(llt.info() == Eigen::Success);
      // The factor inside a larger block whose strict upper triangle is garbage: it is not read.
      const Eigen::Index ld = n + 3;
      Eigen::MatrixXd F = Eigen::MatrixXd::Constant(ld, n, std::numeric_limits<double>::quiet_NaN());
      F.topRows(n).triangularView<Eigen::Lower>() = llt.matrixL();
      const double aNorm = A.cwiseAbs().colwise().sum().maxCoeff();
      const double rcond = choleskyReciprocalCondition(aNorm, F.data(), n, ld);
      // Eigen's steps, so Eigen's value up to the solves' rounding (relative cond · ε ≤ 1e-5 here).
      CHECK(std::abs(rcond / llt.rcond() - 1) <= 1e-3);
      // LAPACK's dpocon makes the same kind of estimate (dlacn2): within a factor 3 of it.
      Eigen::MatrixXd L = llt.matrixLLT();
      double lapack = 0;
      REQUIRE(LAPACKE_dpocon(LAPACK_COL_MAJOR, 'L', int(n), L.data(), int(n), aNorm, &lapack) == 0);
      CHECK(rcond <= 3 * lapack);
      CHECK(rcond >= lapack / 3);
      // An estimate of ‖A⁻¹‖₁ from below: rcond is at least the true reciprocal condition.
      const double inverseNorm = choleskyInverseNormEstimate(F.data(), n, ld);
      CHECK(inverseNorm <= trueInverseOneNorm(A) * (1 + 1e-3));
      CHECK(inverseNorm >= trueInverseOneNorm(A) / 3);
    }
  }
}

TEST_CASE("the Cholesky condition estimate follows Eigen's conventions at n = 0 and 1 and for a zero norm") {
  const double one = 2.0;
  CHECK(std::isinf(choleskyReciprocalCondition(1.0, nullptr, 0, 0)));
  CHECK(choleskyReciprocalCondition(4.0, &one, 1, 1) == 1);
  CHECK(choleskyReciprocalCondition(0.0, &one, 1, 1) == 0);
  CHECK(choleskyInverseNormEstimate(&one, 1, 1) == doctest::Approx(0.25).epsilon(1e-15));  // A = 4
  CHECK(choleskyInverseNormEstimate(nullptr, 0, 0) == 0);
}
