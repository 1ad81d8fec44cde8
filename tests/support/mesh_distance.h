#pragma once
// The distance from points to a triangle mesh by brute force over its triangles: the reference
// the tests compare meshes and faster queries with.

#include <algorithm>
#include <limits>

#include "core/mesh/tri_mesh.h"
#include "core/mesh/triangle_distance.h"

namespace hermite::testing {

// Distance from x to the nearest triangle of m (faces, edges and corners); ∞ without triangles.
inline double bruteMeshDistance(const TriMesh& m, const Vec<3>& x) {
  double d = std::numeric_limits<double>::infinity();
  for (int t = 0; t < m.triangleCount(); ++t)
    d = std::min(d, pointTriangleDistance(x, m.vertices.col(m.triangles(0, t)), m.vertices.col(m.triangles(1, t)),
                                          m.vertices.col(m.triangles(2, t))));
  return d;
}

// The largest distance from a column of `points` to m (bruteMeshDistance); 0 without points.
inline double farthestFromMesh(const TriMesh& m, const Points<3>& points) {
  double worst = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) worst = std::max(worst, bruteMeshDistance(m, points.col(i)));
  return worst;
}

}  // namespace hermite::testing
