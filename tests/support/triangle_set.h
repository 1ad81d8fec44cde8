#pragma once
// Two meshes compared triangle for triangle, whatever the order of their vertices and triangles.

#include <algorithm>
#include <array>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace hermite::testing {

using Triangle = std::array<std::array<double, 3>, 3>;

// The mesh's triangles by their corners' coordinates, each with its corners rotated to start at
// the least (orientation kept), sorted: equal for two meshes with the same triangles.
inline std::vector<Triangle> triangleSet(const TriMesh& mesh) {
  std::vector<Triangle> out;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    Triangle tri;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) tri[k][a] = mesh.vertices(a, mesh.triangles(k, t));
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace hermite::testing
