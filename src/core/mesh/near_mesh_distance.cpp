#include "core/mesh/near_mesh_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <omp.h>

#include "core/base/radix_sort.h"
#include "core/mesh/triangle_distance.h"

namespace hermite {

namespace {

constexpr int kRegionCells = 64;         // cubes along the region's longest side, at most
constexpr std::int64_t kMaxCubes = 512;  // a triangle filling more cubes is tested at every point

// The triangles of a mesh bucketed in a uniform grid of cubes over `region` (the points' box): a
// triangle is in every cube that its bounding box, grown by `reach` and clipped to the region,
// touches, so the triangles within `reach` of a point of the region are all in the point's own
// cube. Cubes are at least 1/kRegionCells of the region's longest side, so the grid stays small
// however small the reach; a triangle that would fill more than kMaxCubes cubes is listed apart.
class TriangleBuckets {
 public:
  TriangleBuckets(const TriMesh& mesh, const Box<3>& region, double reach) : origin_(region.lo) {
    cube_ = std::max(reach, region.extent().maxCoeff() / kRegionCells);
    if (!(cube_ > 0)) cube_ = 1;  // one point and no reach: any cube holds it
    for (int k = 0; k < 3; ++k) n_[k] = static_cast<int>(std::floor(region.extent()[k] / cube_)) + 1;
    // Each thread buckets a contiguous range of triangles; joined in thread order, the lists are
    // those of one pass over the triangles.
    std::vector<Lists> parts(static_cast<std::size_t>(omp_get_max_threads()));
    const int m = mesh.triangleCount();
#pragma omp parallel
    {
      Lists& mine = parts[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
      for (int t = 0; t < m; ++t) bucket(mesh, t, region, reach, mine);
    }
    for (const Lists& part : parts) {
      byCube_.insert(byCube_.end(), part.byCube.begin(), part.byCube.end());
      large_.insert(large_.end(), part.large.begin(), part.large.end());
    }
    radixSort(byCube_);  // (key, triangle) pairs are distinct: any sort gives this order
  }

  // Calls visit(t) for each triangle that may lie within reach of p (a point of the region).
  template <class Visit>
  void near(const Vec<3>& p, Visit&& visit) const {
    for (int t : large_) visit(t);
    const std::int64_t k = key(cubeOf(p));
    for (auto it = std::lower_bound(byCube_.begin(), byCube_.end(), std::make_pair(k, -1));
         it != byCube_.end() && it->first == k; ++it)
      visit(it->second);
  }

 private:
  struct Lists {
    std::vector<std::pair<std::int64_t, int>> byCube;
    std::vector<int> large;
  };

  // Lists triangle t in the cubes its bounding box, grown by `reach` and clipped to the region,
  // touches, or apart when they are more than kMaxCubes.
  void bucket(const TriMesh& mesh, int t, const Box<3>& region, double reach, Lists& out) const {
    Vec<3> lo = mesh.vertices.col(mesh.triangles(0, t)), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(mesh.vertices.col(mesh.triangles(c, t)));
      hi = hi.cwiseMax(mesh.vertices.col(mesh.triangles(c, t)));
    }
    lo = (lo.array() - reach).matrix().cwiseMax(region.lo);
    hi = (hi.array() + reach).matrix().cwiseMin(region.hi);
    if (!lo.allFinite() || !hi.allFinite() || (lo.array() > hi.array()).any()) return;  // beyond reach
    const std::array<int, 3> a = cubeOf(lo), b = cubeOf(hi);
    if (std::int64_t(b[0] - a[0] + 1) * (b[1] - a[1] + 1) * (b[2] - a[2] + 1) > kMaxCubes) {
      out.large.push_back(t);
      return;
    }
    for (int z = a[2]; z <= b[2]; ++z)
      for (int y = a[1]; y <= b[1]; ++y)
        for (int x = a[0]; x <= b[0]; ++x) out.byCube.emplace_back(key({x, y, z}), t);
  }

  std::array<int, 3> cubeOf(const Vec<3>& p) const {
    std::array<int, 3> c;
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<int>(std::floor((p[k] - origin_[k]) / cube_)), 0, n_[k] - 1);
    return c;
  }
  std::int64_t key(const std::array<int, 3>& c) const {
    return c[0] + std::int64_t(n_[0]) * (c[1] + std::int64_t(n_[1]) * c[2]);
  }

  Vec<3> origin_;
  double cube_ = 1;
  std::array<int, 3> n_{};                            // cubes per axis
  std::vector<std::pair<std::int64_t, int>> byCube_;  // (cube key, triangle), sorted
  std::vector<int> large_;
};

}  // namespace

std::vector<double> distancesToMeshWithin(const TriMesh& mesh, const Points<3>& points, double reach) {
  std::vector<double> out(static_cast<std::size_t>(points.cols()), reach);
  Box<3> region{Vec<3>::Constant(std::numeric_limits<double>::infinity()),
                Vec<3>::Constant(-std::numeric_limits<double>::infinity())};
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    if (!points.col(i).allFinite()) continue;
    region.lo = region.lo.cwiseMin(points.col(i));
    region.hi = region.hi.cwiseMax(points.col(i));
  }
  if (!(region.lo.array() <= region.hi.array()).all() || mesh.triangleCount() == 0) return out;
  const TriangleBuckets buckets(mesh, region, reach);
  const auto vertex = [&](int t, int k) -> Vec<3> { return mesh.vertices.col(mesh.triangles(k, t)); };
  const Eigen::Index n = points.cols();
#pragma omp parallel for schedule(dynamic, 1024)
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec<3> p = points.col(i);
    if (!p.allFinite()) continue;
    double& best = out[static_cast<std::size_t>(i)];
    // A NaN distance (a triangle that is not finite) leaves best as it is.
    buckets.near(p, [&](int t) {
      best = std::min(best, pointTriangleDistance(p, vertex(t, 0), vertex(t, 1), vertex(t, 2)));
    });
  }
  return out;
}

}  // namespace hermite
