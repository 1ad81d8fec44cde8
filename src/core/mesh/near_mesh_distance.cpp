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
    // Clamped so that the cast stays defined; cells that far apart wrap in key() and only cost
    // distance tests, which are exact.
    constexpr double kFar = 1e15;
    for (int k = 0; k < 3; ++k)
      c[k] = static_cast<std::int64_t>(std::clamp(std::floor((p[k] - origin[k]) / edge), -kFar, kFar));
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
    if (!points.col(i).allFinite()) continue;
    const std::array<std::int64_t, 3> c = cells.of(points.col(i));
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) keys.push_back(CellKeys::key(c[0] + dx, c[1] + dy, c[2] + dz));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

// Triangles whose bounding box spans more cells than this are measured against every point.
constexpr std::int64_t kMaxBucketCells = 64;

// The triangles bucketed by cell: (cell key, triangle) for every cell of a triangle's bounding box
// that lies in `wanted`, sorted; the triangles spanning more than kMaxBucketCells cells (or
// not finite) in `large`.
struct Buckets {
  std::vector<std::pair<std::int64_t, int>> byCell;
  std::vector<int> large;
};

Buckets bucketTriangles(const TriMesh& mesh, const CellKeys& cells, const std::vector<std::int64_t>& wanted) {
  Buckets out;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    Vec<3> lo = mesh.vertices.col(mesh.triangles(0, t)), hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.vertices.col(mesh.triangles(k, t)));
      hi = hi.cwiseMax(mesh.vertices.col(mesh.triangles(k, t)));
    }
    const Vec<3> span = (hi - lo) / cells.edge;
    if (!span.allFinite() || !lo.allFinite() || (span.array() + 2).prod() > double(kMaxBucketCells)) {
      out.large.push_back(t);
      continue;
    }
    const std::array<std::int64_t, 3> a = cells.of(lo), b = cells.of(hi);
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t x = a[0]; x <= b[0]; ++x) {
          const std::int64_t key = CellKeys::key(x, y, z);
          if (std::binary_search(wanted.begin(), wanted.end(), key)) out.byCell.emplace_back(key, t);
        }
  }
  std::sort(out.byCell.begin(), out.byCell.end());
  return out;
}

}  // namespace

std::vector<double> distancesToMeshWithin(const TriMesh& mesh, const Points<3>& points, double reach) {
  std::vector<double> out(static_cast<std::size_t>(points.cols()), reach);
  if (points.cols() == 0 || mesh.triangleCount() == 0) return out;
  Vec<3> origin = Vec<3>::Zero();
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (points.col(i).allFinite()) origin = points.col(i);
  const CellKeys cells{origin, reach};
  const Buckets buckets = bucketTriangles(mesh, cells, neighbourhoodKeys(cells, points));
  const std::vector<std::pair<std::int64_t, int>>& byCell = buckets.byCell;
  const auto vertex = [&](int t, int k) -> Vec<3> { return mesh.vertices.col(mesh.triangles(k, t)); };
  const auto distance = [&](const Vec<3>& p, int t) {
    return pointTriangleDistance(p, vertex(t, 0), vertex(t, 1), vertex(t, 2));
  };
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Vec<3> p = points.col(i);
    if (!p.allFinite()) continue;
    const std::array<std::int64_t, 3> c = cells.of(p);
    double& best = out[static_cast<std::size_t>(i)];
    for (int t : buckets.large) best = std::min(best, distance(p, t));  // a NaN distance leaves best
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::int64_t key = CellKeys::key(c[0] + dx, c[1] + dy, c[2] + dz);
          auto it = std::lower_bound(byCell.begin(), byCell.end(), std::make_pair(key, -1));
          for (; it != byCell.end() && it->first == key; ++it) best = std::min(best, distance(p, it->second));
        }
  }
  return out;
}

}  // namespace hermite
