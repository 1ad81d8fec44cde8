#include "app/commands/bench_lapack.h"

#include <lapacke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

namespace hermite {

namespace {

bool usesLu(SolverChoice path) { return path == SolverChoice::Lu || path == SolverChoice::Ldlt; }

}  // namespace

Eigen::Index factorisedSize(SolverChoice path, double flops) {
  const double k = std::cbrt((usesLu(path) ? 1.5 : 3.0) * flops);
  return static_cast<Eigen::Index>(std::llround(k));
}

double plainLapackGflops(SolverChoice path, Eigen::Index k, int repeats) {
  if (k < 1) return 0;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr(k, k, [&] { return u(rng); });
  M = (M + M.transpose()).eval();
  M.diagonal().array() += double(k);  // diagonally dominant: positive definite, no pivoting trouble
  std::vector<double> ms;
  std::vector<lapack_int> ipiv(static_cast<std::size_t>(k));
  const lapack_int n = static_cast<lapack_int>(k);
  for (int r = 0; r < std::max(1, repeats); ++r) {
    Eigen::MatrixXd A = M;
    const auto t0 = std::chrono::steady_clock::now();
    if (usesLu(path))
      LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n, n, A.data(), n, ipiv.data());
    else
      LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', n, A.data(), n);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return factorisationFlops(usesLu(path) ? SolverChoice::Lu : SolverChoice::Cholesky, k) / (ms[ms.size() / 2] * 1e6);
}

}  // namespace hermite
