#include "core/points/uniform_winding.h"

#include <algorithm>
#include <cmath>

namespace hermite {

namespace {

// Query points per pass over the samples: 200 000 samples are 9.6 MB, past the caches, and a
// pass per point spent its time reading them.
constexpr int kBlock = 8;

// w at cols[0 … count − 1] (count ≤ kBlock) into w[0 … count − 1]. Each point's sum runs over the
// samples in order; the points of a block are the lanes of one vector loop.
void windingBlock(const HermiteSamples<3>& samples, double spacing, const Points<3>& X, const Eigen::Index* cols,
                  int count, double* w) {
  double qx[kBlock], qy[kBlock], qz[kBlock], sum[kBlock];
  for (int b = 0; b < kBlock; ++b) {
    const Eigen::Index c = cols[std::min(b, count - 1)];  // the last point repeats in unused lanes
    qx[b] = X(0, c), qy[b] = X(1, c), qz[b] = X(2, c), sum[b] = 0;
  }
  const double eps2 = 0.25 * spacing * spacing;
  const double* p = samples.points.data();
  const double* nr = samples.normals.data();
  for (Eigen::Index i = 0; i < samples.points.cols(); ++i, p += 3, nr += 3) {
#pragma omp simd
    for (int b = 0; b < kBlock; ++b) {
      const double dx = p[0] - qx[b], dy = p[1] - qy[b], dz = p[2] - qz[b];
      const double r2 = dx * dx + dy * dy + dz * dz + eps2;
      sum[b] += (dx * nr[0] + dy * nr[1] + dz * nr[2]) / (r2 * std::sqrt(r2));
    }
  }
  for (int b = 0; b < count; ++b) w[b] = spacing * spacing * sum[b] / (4 * M_PI);
}

}  // namespace

std::vector<double> uniformAreaWinding(const HermiteSamples<3>& samples, double spacing, const Points<3>& X,
                                       const std::vector<Eigen::Index>& cols) {
  const int count = static_cast<int>(cols.size());
  std::vector<double> w(cols.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < count; b += kBlock)
    windingBlock(samples, spacing, X, cols.data() + b, std::min(kBlock, count - b), w.data() + b);
  return w;
}

}  // namespace hermite
