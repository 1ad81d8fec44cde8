// The dense solver's paths: projected Cholesky for conditionally definite kernels without their
// polynomial, the panelled (cancellable) factorisations, cancellation, and auto's choices.

#include <doctest/doctest.h>

#include <chrono>
#include <limits>
#include <random>
#include <thread>

#include "core/base/cancel_token.h"
#include "core/rbf/dense_solver.h"
#include "core/rbf/hrbf.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// A random symmetric n × n matrix with `negative` negative eigenvalues of size about 1 and the
// rest positive (in the lower triangle; solveSaddle mirrors it).
SaddleSystem randomSymmetric(Eigen::Index n, int negative, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd X(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) X(i, j) = g(rng);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(X);
  const Eigen::MatrixXd Q = qr.householderQ();
  Eigen::VectorXd d(n);
  for (Eigen::Index i = 0; i < n; ++i) d(i) = (i < negative ? -1.0 : 1.0) * (1.0 + double(i % 7));
  SaddleSystem sys;
  sys.A = Q * d.asDiagonal() * Q.transpose();
  sys.P.resize(n, 0);
  sys.b = Eigen::VectorXd::NullaryExpr(n, [&] { return g(rng); });
  sys.definiteSign = negative == 0 ? 1 : 0;
  return sys;
}

// A symmetric n×n system with `negative` negative diagonal entries, kept nonsingular by diagonal
// dominance (off-diagonal entries in (-1, 1)/n). O(n²) to build, for tests that need a large system
// but not a known spectrum (under ASan the QR above costs minutes at n = 2600).
SaddleSystem dominantSymmetric(Eigen::Index n, int negative, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SaddleSystem sys;
  sys.A.resize(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = j + 1; i < n; ++i) sys.A(i, j) = sys.A(j, i) = u(rng) / double(n);
    sys.A(j, j) = (j < negative ? -1.0 : 1.0) * (1.0 + double(j % 7));
  }
  sys.P.resize(n, 0);
  sys.b = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
  sys.definiteSign = negative == 0 ? 1 : 0;
  return sys;
}

double relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("projected Cholesky solves conditionally definite kernels without their polynomial") {
  const HermiteSamples<3> s = testing::blob(40);
  for (const Kernel& kernel : {Kernel{KernelType::Cubic, 1.0}, Kernel{KernelType::Multiquadric, 0.8},
                               Kernel{KernelType::Polyharmonic, 1.0}}) {
    CAPTURE(kernelName(kernel.type));
    FitReport projected, lu;
    const HrbfModel<3> a = fitHrbf<3>(s, {kernel, Polynomial::None, 0.0, SolverChoice::Auto}, &projected);
    const HrbfModel<3> b = fitHrbf<3>(s, {kernel, Polynomial::None, 0.0, SolverChoice::Lu}, &lu);
    CHECK(projected.solver == "projected-cholesky");
    CHECK(lu.solver == "lu");
    const double scale = b.alpha().cwiseAbs().maxCoeff() + b.beta().cwiseAbs().maxCoeff();
    CHECK((a.alpha() - b.alpha()).cwiseAbs().maxCoeff() <= 1e-8 * scale);
    CHECK((a.beta() - b.beta()).cwiseAbs().maxCoeff() <= 1e-8 * scale);
    // Both are 1-norm estimates of the same matrix's condition.
    CHECK(projected.conditionEstimate >= 0.1 * lu.conditionEstimate);
    CHECK(projected.conditionEstimate <= 10 * lu.conditionEstimate);
    Eigen::VectorXd f;
    Points<3> G;
    a.evaluateBatch(s.points, f, &G);
    CHECK(f.cwiseAbs().maxCoeff() <= 1e-9);
    CHECK((G - s.normals).cwiseAbs().maxCoeff() <= 1e-8);
  }
}

TEST_CASE("projected Cholesky falls back to LU when the samples cannot determine the kernel's polynomial") {
  HermiteSamples<3> s = testing::blob(2);  // 8 unknowns, 4 linear terms: the trailing block is too small to matter
  s.points.col(1) = s.points.col(0) + Vec<3>(1e-3, 0, 0);
  FitReport rep;
  const HrbfModel<3> m = fitHrbf<3>(s, {{KernelType::Cubic, 1.0}, Polynomial::None, 0.0, SolverChoice::Auto}, &rep);
  CHECK((rep.solver == "projected-cholesky" || rep.solver == "lu"));
  CHECK(std::abs(m.value(s.points.col(0))) <= 1e-6);
}

TEST_CASE("auto picks LU rather than LDLT for an indefinite system it cannot project") {
  CHECK(plannedSolverPath(SolverChoice::Auto, 0, 0) == SolverChoice::Lu);
  CHECK(plannedSolverPath(SolverChoice::Auto, 4, 0) == SolverChoice::Lu);
  CHECK(plannedSolverPath(SolverChoice::Auto, 0, 0, true) == SolverChoice::ProjectedCholesky);
  CHECK(plannedSolverPath(SolverChoice::Auto, 0, 1, true) == SolverChoice::Cholesky);
  CHECK(plannedSolverPath(SolverChoice::ProjectedCholesky, 4, 0, true) == SolverChoice::Lu);
  CHECK(plannedSolverPath(SolverChoice::Ldlt, 0, 0) == SolverChoice::Ldlt);
}

TEST_CASE("the panelled factorisations a cancel token selects agree with LAPACK's") {
  const CancelToken token;  // never set: only selects the panelled code
  for (const auto& [n, negative] : {std::pair<Eigen::Index, int>{700, 0}, {1300, 0}, {700, 5}, {1031, 3}}) {
    CAPTURE(n);
    CAPTURE(negative);
    const SolverChoice path = negative == 0 ? SolverChoice::Cholesky : SolverChoice::Lu;
    const SaddleSystem plain = randomSymmetric(n, negative, unsigned(n));
    SaddleSystem panelled = plain;
    panelled.cancel = &token;
    const SaddleSolution a = solveSaddle(plain, path);
    const SaddleSolution b = solveSaddle(panelled, path);
    CHECK(a.solver == std::string(solverName(path)));
    CHECK(b.solver == a.solver);
    CHECK(relativeDifference(b.x, a.x) <= 1e-10);
    CHECK(b.conditionEstimate == doctest::Approx(a.conditionEstimate).epsilon(1e-6));
  }
}

TEST_CASE("a cancelled factorisation throws Cancelled soon after the token is set") {
  CancelToken token;
  SaddleSystem sys = dominantSymmetric(2600, 2, 7);
  sys.cancel = &token;
  token.cancel();
  CHECK_THROWS_AS(solveSaddle(sys, SolverChoice::Lu), Cancelled);
  token.reset();
  std::chrono::steady_clock::time_point set{};
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    set = std::chrono::steady_clock::now();
    token.cancel();
  });
  bool cancelled = false;
  try {
    solveSaddle(sys, SolverChoice::Lu);
  } catch (const Cancelled&) {
    cancelled = true;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - set).count();
  canceller.join();
  CHECK(cancelled);
  MESSAGE("LU of 2600 unknowns stopped ", ms, " ms after cancel()");
  CHECK(ms < 1000);  // a hang guard on a shared machine; docs/performance.md has the measured time
}

TEST_CASE("with assembleLower the Cholesky paths never read A's upper triangle, and a failure rebuilds A") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Positive definite: solved without reading the upper triangle (NaN there) or rebuilding.
  SaddleSystem sys = randomSymmetric(300, 0, 3);
  const SaddleSystem reference = sys;
  const Eigen::MatrixXd assembled = sys.A;
  int rebuilds = 0;
  const auto rebuild = [&](Eigen::MatrixXd& A) {
    ++rebuilds;
    A.triangularView<Eigen::Lower>() = assembled.triangularView<Eigen::Lower>();
  };
  sys.A.triangularView<Eigen::StrictlyUpper>().setConstant(nan);
  sys.assembleLower = rebuild;
  const SaddleSolution a = solveSaddle(sys, SolverChoice::Cholesky);
  CHECK(a.solver == "cholesky");
  CHECK(rebuilds == 0);
  CHECK(relativeDifference(a.x, solveSaddle(reference, SolverChoice::Cholesky).x) <= 1e-13);

  // Claimed definite but indefinite: the Cholesky fails, A is rebuilt and LU solves the original.
  SaddleSystem bad = randomSymmetric(300, 3, 4);
  bad.definiteSign = 1;
  const SaddleSystem badReference = bad;
  const Eigen::MatrixXd badAssembled = bad.A;
  bad.A.triangularView<Eigen::StrictlyUpper>().setConstant(nan);
  bad.assembleLower = [&](Eigen::MatrixXd& A) {
    ++rebuilds;
    A.triangularView<Eigen::Lower>() = badAssembled.triangularView<Eigen::Lower>();
  };
  const SaddleSolution b = solveSaddle(bad, SolverChoice::Cholesky);
  CHECK(b.solver == "lu");
  CHECK(rebuilds == 1);
  CHECK(relativeDifference(b.x, solveSaddle(badReference, SolverChoice::Lu).x) <= 1e-13);
}
