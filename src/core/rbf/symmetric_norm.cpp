#include "core/rbf/symmetric_norm.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hermite {

namespace {

using Index = Eigen::Index;

// Adds |M(r, c)| for the stored columns c in [c0, c1) to sums: to sums[c] for every row r ≥ c,
// and to sums[r] for r > c (the same entry as M(c, r) of the upper triangle).
void addColumnSums(const double* M, Index k, Index ld, Index c0, Index c1, double* sums) {
  for (Index c = c0; c < c1; ++c) {
    const double* col = M + c * ld;
    double own = std::abs(col[c]);
    for (Index r = c + 1; r < k; ++r) {
      const double v = std::abs(col[r]);
      own += v;
      sums[r] += v;
    }
    sums[c] += own;
  }
}

// The first column of part p of `parts`, splitting the triangle's k(k+1)/2 entries evenly:
// column c holds k − c entries, so part boundaries sit at k(1 − √(1 − p/parts)).
Index partStart(Index k, int p, int parts) {
  if (p >= parts) return k;
  const double f = 1.0 - std::sqrt(1.0 - double(p) / double(parts));
  return std::min(k, Index(std::floor(double(k) * f)));
}

}  // namespace

double lowerSymmetricOneNorm(const double* M, Index k, Index ld) {
  if (k <= 0) return 0;
  // Below about 256² entries the threads' start costs more than the pass.
  const int parts = k < 256 ? 1 : std::max(1, omp_get_max_threads());
  std::vector<double> sums(std::size_t(parts) * std::size_t(k), 0.0);
#pragma omp parallel for num_threads(parts) schedule(static, 1)
  for (int p = 0; p < parts; ++p)
    addColumnSums(M, k, ld, partStart(k, p, parts), partStart(k, p + 1, parts), sums.data() + std::size_t(p) * k);
  double norm = 0;
  for (Index j = 0; j < k; ++j) {
    double s = 0;
    for (int p = 0; p < parts; ++p) s += sums[std::size_t(p) * k + j];
    if (!std::isfinite(s)) return std::numeric_limits<double>::quiet_NaN();
    norm = std::max(norm, s);
  }
  return norm;
}

}  // namespace hermite
