#include <doctest/doctest.h>

#include <limits>

#include "core/rbf/hrbf.h"
#include "core/rbf/kept_kernel_matrix.h"
#include "support/test_data.h"

using namespace hermite;
using hermite::testing::blob;

namespace {

// A kept matrix of n × n whose every entry is NaN: a fit that read anything it did not write
// itself would produce NaN coefficients (solveSaddle throws on a non-finite solution).
void keepPoisonedMatrix(Eigen::Index n) {
  Eigen::MatrixXd A = takeKernelMatrix(n);
  A.setConstant(std::numeric_limits<double>::quiet_NaN());
  keepKernelMatrix(std::move(A));
  REQUIRE(keptKernelMatrixBytes() == sizeof(double) * std::size_t(n * n));
}

double maxRelativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  REQUIRE(a.size() == b.size());
  const double scale = std::max(a.cwiseAbs().maxCoeff(), 1e-300);
  return (a - b).cwiseAbs().maxCoeff() / scale;
}

}  // namespace

TEST_CASE("takeKernelMatrix returns the kept matrix of the same size and frees one of another size") {
  releaseKeptKernelMatrix();
  const Eigen::Index n = 1100;  // 9.7 MB: within the kept bounds
  Eigen::MatrixXd A = takeKernelMatrix(n);
  CHECK(A.rows() == n);
  CHECK(A.cols() == n);
  const double* storage = A.data();
  keepKernelMatrix(std::move(A));
  CHECK(keptKernelMatrixBytes() == sizeof(double) * std::size_t(n * n));
  Eigen::MatrixXd B = takeKernelMatrix(n);
  CHECK(B.data() == storage);
  CHECK(keptKernelMatrixBytes() == 0);
  keepKernelMatrix(std::move(B));
  const Eigen::MatrixXd C = takeKernelMatrix(n + 4);
  CHECK(C.rows() == n + 4);
  CHECK(keptKernelMatrixBytes() == 0);  // the kept one of the other size was freed
}

TEST_CASE("matrices outside the kept bounds, and non-square ones, are not kept") {
  releaseKeptKernelMatrix();
  keepKernelMatrix(Eigen::MatrixXd(100, 100));  // 80 kB: below kMinKeptKernelMatrixBytes
  CHECK(keptKernelMatrixBytes() == 0);
  keepKernelMatrix(Eigen::MatrixXd(2000, 1000));  // 16 MB but not square
  CHECK(keptKernelMatrixBytes() == 0);
  CHECK(releaseKeptKernelMatrix() == 0);
}

TEST_CASE("a refit into the kept kernel matrix gives the coefficients of a fit into a fresh one") {
  // 300 samples: 1 200 kernel unknowns, an 11.5 MB kernel block (kept). Each solver path that
  // builds its matrix in the kept storage: nullspace-cholesky (cubic + linear), projected-cholesky
  // (cubic, no polynomial), cholesky (gaussian), lu (forced, mirrors the lower triangle).
  const HermiteSamples<3> s = blob(300);
  struct Case {
    HrbfOptions options;
    const char* solver;
  };
  const Case cases[] = {
      {{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0, SolverChoice::Auto}, "nullspace-cholesky"},
      {{{KernelType::Cubic, 1.0}, Polynomial::None, 0.0, SolverChoice::Auto}, "projected-cholesky"},
      {{{KernelType::Gaussian, 0.6}, Polynomial::None, 1e-8, SolverChoice::Auto}, "cholesky"},
      {{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0, SolverChoice::Lu}, "lu"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.solver);
    releaseKeptKernelMatrix();
    FitReport fresh, reused;
    const HrbfModel<3> a = fitHrbf<3>(s, c.options, &fresh);
    CHECK(fresh.solver == c.solver);
    keepPoisonedMatrix(Eigen::Index(s.size()) * 4);
    const HrbfModel<3> b = fitHrbf<3>(s, c.options, &reused);
    CHECK(reused.solver == c.solver);
    CHECK(maxRelativeDifference(a.alpha(), b.alpha()) <= 1e-12);
    const Eigen::VectorXd betaA = a.beta().reshaped(), betaB = b.beta().reshaped();
    CHECK(maxRelativeDifference(betaA, betaB) <= 1e-12);
    REQUIRE(a.poly().size() == b.poly().size());
    if (a.poly().size() > 0) CHECK(maxRelativeDifference(a.poly(), b.poly()) <= 1e-12);
    CHECK(reused.conditionEstimate == doctest::Approx(fresh.conditionEstimate).epsilon(1e-9));
  }
  releaseKeptKernelMatrix();
}

TEST_CASE("a dense fit keeps its kernel matrix for the next fit of the same size") {
  releaseKeptKernelMatrix();
  const HermiteSamples<3> s = blob(300);
  fitHrbf<3>(s, HrbfOptions{});
  CHECK(keptKernelMatrixBytes() == sizeof(double) * 1200u * 1200u);
  releaseKeptKernelMatrix();
}
