// The fit-speed yardstick ("unit"): the median wall time of a 1000 × 1000 Eigen LU with partial
// pivoting, single thread, -O2, on a fixed random matrix. Whole-process fit times in
// docs/performance.md are given in these units, measured in the same run, so that they compare
// across machines and loads. Prints the median in milliseconds.

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

int main() {
  Eigen::setNbThreads(1);
  std::srand(1);
  const Eigen::MatrixXd M = Eigen::MatrixXd::Random(1000, 1000) + 1000.0 * Eigen::MatrixXd::Identity(1000, 1000);
  std::vector<double> ms;
  double sink = 0;
  for (int repeat = 0; repeat < 7; ++repeat) {
    const auto t0 = std::chrono::steady_clock::now();
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    sink += lu.matrixLU()(999, 999);
  }
  std::sort(ms.begin(), ms.end());
  std::printf("%.2f\n", ms[ms.size() / 2]);
  return sink == 0.123456 ? 1 : 0;  // keeps the factorisation from being optimised away
}
