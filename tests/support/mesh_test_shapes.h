#pragma once
// Test meshes for the mesh tests: the core shapes, and removal of chosen triangles.

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"
#include "core/shapes/mesh_shapes.h"

namespace hermite::testing {

// The closed torus and ball cutting come from core (core/shapes/mesh_shapes.h), shared with the
// hole-filling presets and bench.
inline TriMesh parametricTorus(int nu, int nv, double R = 0.7, double r = 0.3) { return parametricTorusMesh(nu, nv, R, r); }
using hermite::cutBall;

// The mesh without the triangles `drop` says yes to (vertices are kept, ids unchanged).
template <class Pred>
TriMesh removeTriangles(const TriMesh& mesh, Pred drop) {
  std::vector<int> keep;
  for (int t = 0; t < mesh.triangleCount(); ++t)
    if (!drop(t)) keep.push_back(t);
  TriMesh out = mesh;
  out.triangles.resize(3, static_cast<Eigen::Index>(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k) out.triangles.col(static_cast<Eigen::Index>(k)) = mesh.triangles.col(keep[k]);
  return out;
}

// `mesh` with `piece` appended (its vertex ids shifted), moved by `offset`; no normals.
inline TriMesh withPiece(const TriMesh& mesh, TriMesh piece, const Vec<3>& offset) {
  TriMesh out = mesh;
  const int base = mesh.vertexCount();
  piece.vertices.colwise() += offset;
  out.vertices.conservativeResize(3, base + piece.vertexCount());
  out.vertices.rightCols(piece.vertexCount()) = piece.vertices;
  piece.triangles.array() += base;
  out.triangles.conservativeResize(3, mesh.triangleCount() + piece.triangleCount());
  out.triangles.rightCols(piece.triangleCount()) = piece.triangles;
  out.normals.resize(3, 0);
  return out;
}

// The smallest angle, degrees, of triangles firstTriangle … end of `mesh` (180 when there are none).
inline double smallestAngleDegrees(const TriMesh& mesh, int firstTriangle) {
  double smallest = 180;
  for (int t = firstTriangle; t < mesh.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const Vec<3> p = mesh.vertices.col(mesh.triangles(c, t));
      const Vec<3> u = Vec<3>(mesh.vertices.col(mesh.triangles((c + 1) % 3, t))) - p;
      const Vec<3> v = Vec<3>(mesh.vertices.col(mesh.triangles((c + 2) % 3, t))) - p;
      smallest = std::min(smallest, std::acos(std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0)) * 180 / M_PI);
    }
  return smallest;
}

}  // namespace hermite::testing
