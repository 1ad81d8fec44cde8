#include "core/mesh/near_mesh_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "core/mesh/triangle_distance.h"

namespace hermite {

namespace {

// Cells of edge `reach` keyed by their integer coordinates, 21 bits each (offset so that
// negative coordinates stay positive).
struct CellKeys {
  Vec<3> origin;
  double edge = 1;
  std::array<std::int64_t, 3> of(const Vec<3>& p) const {
    std::array<std::int64_t, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = static_cast<std::int64_t>(std::floor((p[k] - origin[k]) / edge));
    return c;
  }
  static std::int64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    constexpr std::int64_t kOffset = std::int64_t(1) << 20, kMask = (std::int64_t(1) << 21) - 1;
    return ((x + kOffset) & kMask) | (((y + kOffset) & kMask) << 21) | (((z + kOffset) & kMask) << 42);
  }
};

// The keys of the cells within one cell of each point's own, sorted and unique.
std::vector<std::int64_t> neighbourhoodKeys(const CellKeys& cells, const Points<3>& points) {
  std::vector<std::int64_t> keys;
  keys.reserve(static_cast<std::size_t>(points.cols()) * 27);
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const std::array<std::int64_t, 3> c = cells.of(points.col(i));
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) keys.push_back(CellKeys::key(c[0] + dx, c[1] + dy, c[2] + dz));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

// (cell key, triangle) for every cell of a triangle's bounding box that lies in `wanted`, sorted.
std::vector<std::pair<std::int64_t, int>> bucketTriangles(const TriMesh& mesh, const CellKeys& cells,
                                                          const std::vector<std::int64_t>& wanted) {
  std::vector<std::pair<std::int64_t, int>> out;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    Vec<3> lo = mesh.vertices.col(mesh.triangles(0, t)), hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.vertices.col(mesh.triangles(k, t)));
      hi = hi.cwiseMax(mesh.vertices.col(mesh.triangles(k, t)));
    }
    const std::array<std::int64_t, 3> a = cells.of(lo), b = cells.of(hi);
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t x = a[0]; x <= b[0]; ++x) {
          const std::int64_t key = CellKeys::key(x, y, z);
          if (std::binary_search(wanted.begin(), wanted.end(), key)) out.emplace_back(key, t);
        }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<double> distancesToMeshWithin(const TriMesh& mesh, const Points<3>& points, double reach) {
  std::vector<double> out(static_cast<std::size_t>(points.cols()), reach);
  if (points.cols() == 0 || mesh.triangleCount() == 0) return out;
  const CellKeys cells{points.rowwise().minCoeff(), reach};
  const std::vector<std::pair<std::int64_t, int>> buckets =
      bucketTriangles(mesh, cells, neighbourhoodKeys(cells, points));
  const auto vertex = [&](int t, int k) -> Vec<3> { return mesh.vertices.col(mesh.triangles(k, t)); };
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Vec<3> p = points.col(i);
    const std::array<std::int64_t, 3> c = cells.of(p);
    double& best = out[static_cast<std::size_t>(i)];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::int64_t key = CellKeys::key(c[0] + dx, c[1] + dy, c[2] + dz);
          auto it = std::lower_bound(buckets.begin(), buckets.end(), std::make_pair(key, -1));
          for (; it != buckets.end() && it->first == key; ++it)
            best = std::min(best, pointTriangleDistance(p, vertex(it->second, 0), vertex(it->second, 1),
                                                        vertex(it->second, 2)));
        }
  }
  return out;
}

}  // namespace hermite
