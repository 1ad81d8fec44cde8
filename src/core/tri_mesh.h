#pragma once
// Triangle meshes (DESIGN.md §2): vertices, triangles, per-vertex normals, and the topology
// queries hole filling and the loaders need (boundary loops, connected components).
// Orientation: triangles are counter-clockwise seen from outside, so the face normal
// (v1 − v0) × (v2 − v0) points outward (the same side as ∇f of an implicit, DESIGN.md §3).

#include <Eigen/Core>
#include <vector>

namespace hermite {

struct TriMesh {
  Eigen::Matrix3Xd vertices;   // 3 × V, one vertex per column
  Eigen::Matrix3Xi triangles;  // 3 × T, vertex indices, counter-clockwise from outside
  Eigen::Matrix3Xd normals;    // 3 × V unit vertex normals, or 3 × 0 when the mesh has none

  int vertexCount() const { return static_cast<int>(vertices.cols()); }
  int triangleCount() const { return static_cast<int>(triangles.cols()); }
  bool hasNormals() const { return normals.cols() == vertices.cols() && vertices.cols() > 0; }
};

}  // namespace hermite
