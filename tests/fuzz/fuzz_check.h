#pragma once
// What every reader promises about a mesh it returns (mesh_format_common.h): finite
// coordinates, indices in range, unit normals for every vertex or none. A broken promise
// aborts, so libFuzzer reports the input.

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/mesh/tri_mesh.h"

namespace hermite::fuzz {

inline void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "reader broke its promise: %s\n", what);
    std::abort();
  }
}

inline void checkMesh(const TriMesh& m) {
  require(m.vertices.allFinite(), "finite vertices");
  require(m.triangles.size() == 0 || (m.triangles.minCoeff() >= 0 && m.triangles.maxCoeff() < m.vertexCount()),
          "indices in range");
  require(m.normals.cols() == 0 || m.normals.cols() == m.vertices.cols(), "one normal per vertex or none");
  for (Eigen::Index i = 0; i < m.normals.cols(); ++i)
    require(std::abs(m.normals.col(i).norm() - 1) < 1e-12, "unit normals");
}

}  // namespace hermite::fuzz
