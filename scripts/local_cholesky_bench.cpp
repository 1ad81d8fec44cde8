// Microbenchmark of the partition of unity's local LLT and its condition estimate
// (docs/performance.md, "Cheaper local factorisations"): Eigen's LLT + rcond() against
// SmallCholesky + rcond() (small_cholesky.h, cholesky_condition.h) on random SPD matrices of the
// local fits' sizes, in microseconds per call (the matrix copy excluded), the variants alternating call by call,
// the fastest of 9 trials.
//
//   cmake --build build/release --target local_cholesky_bench && build/release/local_cholesky_bench
#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "core/rbf/small_cholesky.h"

int main() {
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  double sink = 0;  // keeps the estimates alive
  std::printf("%5s %12s %12s %12s %12s\n", "n", "Eigen LLT", "+ rcond", "SmallChol", "+ rcond");
  for (const int n : {28, 44, 52, 60, 76, 92, 120, 160, 200}) {
    const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return g(rng); });
    const Eigen::MatrixXd A = G * G.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd buf(256, 256);  // as the local fits' per-thread buffer: a larger leading dimension
    const int reps = 4000000 / (n * n * n / 3) + 200;
    // The four variants alternate call by call, so that a loaded host slows each alike; the
    // fastest of 9 trials of `reps` calls each.
    double best[4] = {1e30, 1e30, 1e30, 1e30};
    for (int trial = 0; trial < 9; ++trial) {
      double total[4] = {0, 0, 0, 0};
      for (int r = 0; r < reps; ++r)
        for (int v = 0; v < 4; ++v) {
          buf.topLeftCorner(n, n) = A;
          Eigen::Ref<Eigen::MatrixXd> K = buf.topLeftCorner(n, n);
          const auto t0 = std::chrono::steady_clock::now();
          if (v < 2) {
            const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(K);
            if (v == 1) sink += llt.rcond();
          } else {
            const hermite::SmallCholesky chol(K);
            if (v == 3) sink += chol.rcond();
          }
          total[v] += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
        }
      for (int v = 0; v < 4; ++v) best[v] = std::min(best[v], total[v] / reps);
    }
    std::printf("%5d %12.2f %12.2f %12.2f %12.2f\n", n, best[0], best[1] - best[0], best[2], best[3] - best[2]);
  }
  return sink > 0 ? 0 : 1;
}
