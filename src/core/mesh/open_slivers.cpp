#include "core/mesh/open_slivers.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/parallel_sort.h"

namespace hermite {

namespace {

// Per component: whether one of its edges is used by a single triangle.
std::vector<char> componentsWithBoundary(const TriMesh& mesh, const std::vector<int>& label, int count) {
  std::vector<std::pair<std::uint64_t, int>> edges;  // (edge, triangle)
  edges.reserve(3 * static_cast<size_t>(mesh.triangleCount()));
  for (int t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(mesh.triangles(k, t));
      const auto b = static_cast<std::uint32_t>(mesh.triangles((k + 1) % 3, t));
      edges.emplace_back(std::uint64_t(std::min(a, b)) << 32 | std::max(a, b), t);
    }
  parallelSort(edges.begin(), edges.end());  // (edge, triangle): a strict total order
  std::vector<char> open(static_cast<size_t>(count), 0);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 1) open[static_cast<size_t>(label[static_cast<size_t>(edges[i].second)])] = 1;
    i = j;
  }
  return open;
}

}  // namespace

int dropOpenSlivers(TriMesh& mesh, double maxArea) {
  int count = 0;
  const std::vector<int> label = triangleComponents(mesh, &count);
  if (count <= 1) return 0;  // the whole contour is never dropped
  std::vector<double> area(static_cast<size_t>(count), 0.0);
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t)), b = mesh.vertices.col(mesh.triangles(1, t)),
                          c = mesh.vertices.col(mesh.triangles(2, t));
    area[static_cast<size_t>(label[static_cast<size_t>(t)])] += 0.5 * (b - a).cross(c - a).norm();
  }
  const std::vector<char> open = componentsWithBoundary(mesh, label, count);
  std::vector<char> drop(static_cast<size_t>(count), 0);
  int dropped = 0;
  for (int c = 0; c < count; ++c)
    if (open[static_cast<size_t>(c)] && area[static_cast<size_t>(c)] < maxArea) drop[static_cast<size_t>(c)] = 1, ++dropped;
  if (dropped == 0) return 0;
  Eigen::Index kept = 0;
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    if (!drop[static_cast<size_t>(label[static_cast<size_t>(t)])]) mesh.triangles.col(kept++) = mesh.triangles.col(t);
  mesh.triangles.conservativeResize(3, kept);
  dropUnusedVertices(mesh);
  return dropped;
}

}  // namespace hermite
