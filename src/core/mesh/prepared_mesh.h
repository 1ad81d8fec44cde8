#pragma once
// A triangle mesh with the adjacency and normals hole filling looks up.

#include <vector>

#include <Eigen/Core>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// The original mesh with what every stage looks up: vertex → triangles (CSR) and area-weighted
// vertex normals. Build once per mesh; holds a reference to it.
class PreparedMesh {
 public:
  explicit PreparedMesh(const TriMesh& mesh);
  const TriMesh& mesh() const { return *mesh_; }
  const Eigen::Matrix3Xd& normals() const { return normals_; }  // 3 × V
  // Triangles incident to vertex v.
  const int* trianglesBegin(int v) const { return triangles_.data() + offsets_[v]; }
  const int* trianglesEnd(int v) const { return triangles_.data() + offsets_[v + 1]; }
  // Vertices sharing an edge with v (sorted, unique).
  std::vector<int> neighbours(int v) const;

 private:
  const TriMesh* mesh_;
  Eigen::Matrix3Xd normals_;
  std::vector<int> offsets_;    // V + 1
  std::vector<int> triangles_;  // incident triangle ids, grouped by vertex
};

}  // namespace hermite
