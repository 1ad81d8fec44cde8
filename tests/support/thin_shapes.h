#pragma once
// Closed, outward-oriented meshes with two sheets closer than a sample neighbourhood, for the
// normal-orientation tests and scripts/normal_flips.cpp: thin parts that a propagation copying
// orientations across the gap turns inside out.

#include <cmath>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "core/shapes/mesh_shapes.h"

namespace hermite::testing {

// The closed thin box [0, 1] × [0, 1] × [0, t] with `nx` segments along x (so that it bends),
// counter-clockwise seen from outside: its (x, z) cross-section extruded along y.
inline TriMesh thinBox(int nx, double t) {
  TriMesh m;
  // Cross-section ring: bottom row x = 0..1 at z = 0, then top row x = 1..0 at z = t.
  const int ring = 2 * (nx + 1);
  auto ringPoint = [&](int r) {
    return r <= nx ? Vec<3>(double(r) / nx, 0, 0) : Vec<3>(double(ring - 1 - r) / nx, 0, t);
  };
  m.vertices.resize(3, 2 * ring);
  for (int r = 0; r < ring; ++r) {
    m.vertices.col(r) = ringPoint(r);
    m.vertices.col(ring + r) = ringPoint(r) + Vec<3>(0, 1, 0);
  }
  std::vector<Eigen::Vector3i> tris;
  for (int r = 0; r < ring; ++r) {  // the sides: quads between y = 0 and y = 1
    const int a = r, b = (r + 1) % ring;
    tris.emplace_back(a, b, ring + b);
    tris.emplace_back(a, ring + b, ring + a);
  }
  for (int i = 0; i < nx; ++i) {  // the end caps: strips between the bottom and top rows
    const int b0 = i, b1 = i + 1, t0 = ring - 1 - i, t1 = ring - 2 - i;
    tris.emplace_back(b0, t1, b1);
    tris.emplace_back(b0, t0, t1);
    tris.emplace_back(ring + b0, ring + b1, ring + t1);
    tris.emplace_back(ring + b0, ring + t1, ring + t0);
  }
  m.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (std::size_t k = 0; k < tris.size(); ++k) m.triangles.col(static_cast<Eigen::Index>(k)) = tris[k];
  if (signedVolume(m) < 0) m.triangles.row(1).swap(m.triangles.row(2));
  return m;
}

// The thin box curled about the y axis: x ↦ angle (x − ½)/R, z ↦ radius R + z, R = 1/(1.5π).
inline TriMesh curledPlate(double t) {
  TriMesh m = thinBox(400, t);
  const double R = 1.0 / (1.5 * M_PI);
  for (Eigen::Index v = 0; v < m.vertices.cols(); ++v) {
    const Vec<3> p = m.vertices.col(v);
    const double phi = (p.x() - 0.5) / R, r = R + p.z();
    m.vertices.col(v) = Vec<3>(r * std::sin(phi), p.y(), r * std::cos(phi));
  }
  if (signedVolume(m) < 0) m.triangles.row(1).swap(m.triangles.row(2));
  return m;
}

// The solid between spheres of radius 1 and 1 − t: outward normals outside, inward inside.
inline TriMesh hollowBall(double t) {
  TriMesh outer = uvSphereMesh(256, 128);
  TriMesh inner = outer;
  inner.vertices *= 1 - t;
  inner.triangles.row(1).swap(inner.triangles.row(2));
  TriMesh shell;
  shell.vertices.resize(3, outer.vertexCount() + inner.vertexCount());
  shell.vertices << outer.vertices, inner.vertices;
  shell.triangles.resize(3, outer.triangleCount() + inner.triangleCount());
  shell.triangles << outer.triangles, (inner.triangles.array() + outer.vertexCount()).matrix();
  return shell;
}

}  // namespace hermite::testing
