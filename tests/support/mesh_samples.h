#pragma once
// Points sampled from triangle meshes with their exact normals, for the normal-estimation and
// data-loading tests: uniform by area, seeded.

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <vector>

#include "core/mesh/tri_mesh.h"
#include "core/points/hermite_samples.h"

namespace hermite::testing {

// `count` points uniform by area on the mesh's triangles; each normal is its triangle's unit
// normal (counter-clockwise seen from outside points outward).
inline HermiteSamples<3> sampleMesh(const TriMesh& mesh, int count, unsigned seed) {
  std::vector<double> cumulative;
  double total = 0;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Vec<3> a = mesh.vertices.col(mesh.triangles(0, t)), b = mesh.vertices.col(mesh.triangles(1, t)),
                 c = mesh.vertices.col(mesh.triangles(2, t));
    total += 0.5 * (b - a).cross(c - a).norm();
    cumulative.push_back(total);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  HermiteSamples<3> s;
  s.points.resize(3, count);
  s.normals.resize(3, count);
  for (int i = 0; i < count; ++i) {
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * total);
    const int t = static_cast<int>(std::min<std::ptrdiff_t>(it - cumulative.begin(), mesh.triangleCount() - 1));
    const Vec<3> a = mesh.vertices.col(mesh.triangles(0, t)), b = mesh.vertices.col(mesh.triangles(1, t)),
                 c = mesh.vertices.col(mesh.triangles(2, t));
    double x = u(rng), y = u(rng);
    if (x + y > 1) x = 1 - x, y = 1 - y;
    s.points.col(i) = a + x * (b - a) + y * (c - a);
    s.normals.col(i) = (b - a).cross(c - a).normalized();
  }
  return s;
}

// The closed box [lo, hi], 12 triangles, counter-clockwise seen from outside.
inline TriMesh boxMesh(const Vec<3>& lo, const Vec<3>& hi) {
  TriMesh m;
  m.vertices.resize(3, 8);
  for (int v = 0; v < 8; ++v)
    m.vertices.col(v) = Vec<3>(v & 1 ? hi.x() : lo.x(), v & 2 ? hi.y() : lo.y(), v & 4 ? hi.z() : lo.z());
  m.triangles.resize(3, 12);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int q = 0; q < 6; ++q) {
    m.triangles.col(2 * q) = Eigen::Vector3i(quads[q][0], quads[q][1], quads[q][2]);
    m.triangles.col(2 * q + 1) = Eigen::Vector3i(quads[q][0], quads[q][2], quads[q][3]);
  }
  return m;
}

// The fraction of `estimated` normals (3 × N) pointing against `exact` (n̂·n < 0).
inline double flippedFraction(const Points<3>& estimated, const Points<3>& exact) {
  int flipped = 0;
  for (Eigen::Index i = 0; i < exact.cols(); ++i) flipped += estimated.col(i).dot(exact.col(i)) < 0;
  return double(flipped) / double(exact.cols());
}

}  // namespace hermite::testing
