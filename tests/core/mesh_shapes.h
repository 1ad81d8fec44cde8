#pragma once
// Closed test meshes and hole cutting for the mesh tests (independent of hole filling).

#include <cmath>
#include <vector>

#include "core/geometry.h"
#include "core/tri_mesh.h"

namespace hermite::testing {

// The torus ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) on an nu × nv grid, counter-clockwise
// from outside (∂u × ∂v points outward).
inline TriMesh parametricTorus(int nu, int nv, double R = 0.7, double r = 0.3) {
  TriMesh m;
  m.vertices.resize(3, nu * nv);
  m.triangles.resize(3, 2 * nu * nv);
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.vertices.col(id(i, j)) = Eigen::Vector3d((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
      const int t = 2 * id(i, j);
      m.triangles.col(t) = Eigen::Vector3i(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.triangles.col(t + 1) = Eigen::Vector3i(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

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

// Removes every triangle with a vertex within `radius` of `centre`: one hole per ball.
inline TriMesh cutBall(const TriMesh& mesh, const Eigen::Vector3d& centre, double radius) {
  return removeTriangles(mesh, [&](int t) {
    for (int k = 0; k < 3; ++k)
      if ((mesh.vertices.col(mesh.triangles(k, t)) - centre).norm() < radius) return true;
    return false;
  });
}

}  // namespace hermite::testing
