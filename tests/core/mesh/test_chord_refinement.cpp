#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/mesh/chord_refinement.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "core/shapes/analytic_shapes.h"

using namespace hermite;

namespace {

Box<3> cube(double half) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-half);
  b.hi = Vec<3>::Constant(half);
  return b;
}

// Largest |f| at the triangles' centroids: for a distance field, how far the chords stray from
// the zero set where they stray most.
double worstCentroidGap(const TriMesh& mesh, const ImplicitField<3>& field) {
  double worst = 0;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Vec<3> c = (mesh.vertices.col(mesh.triangles(0, t)) + mesh.vertices.col(mesh.triangles(1, t)) +
                      mesh.vertices.col(mesh.triangles(2, t))) /
                     3;
    worst = std::max(worst, std::abs(field.value(c)));
  }
  return worst;
}

// The refined mesh of a closed marching-cubes mesh: still a closed oriented manifold with the
// same Euler characteristic, every split edge adds one vertex and two triangles, the new vertices
// lie on f = 0, and the chords' worst stray falls to the tolerance: an edge left whole strays at
// most `tolerance` at its midpoint, so a triangle of three such edges strays at most 4/3 of it at
// its centroid (the quadratic through the corners, 4/9 of the sum of its edges' strays).
void checkRefinement(const ImplicitField<3>& field, const TriMesh& mesh, double h, int euler) {
  ChordRefinementOptions options;
  options.tolerance = 0.02 * h;
  ChordRefinementReport report;
  const TriMesh refined = refineChords(mesh, field, options, &report);
  const MeshCheck c = checkMesh(refined);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == euler);
  CHECK(countFlippedTriangles(refined, refined.normals) == 0);
  CHECK(report.splitEdges > 0);
  CHECK(report.unsplitEdges == 0);
  CHECK(refined.vertexCount() == mesh.vertexCount() + report.splitEdges);
  CHECK(refined.triangleCount() == mesh.triangleCount() + 2 * report.splitEdges);
  double worstNew = 0;
  for (int v = mesh.vertexCount(); v < refined.vertexCount(); ++v)
    worstNew = std::max(worstNew, std::abs(field.value(refined.vertices.col(v))));
  // Distance fields: |f| is the distance to the surface; Newton stops within 10⁻⁴ of half an
  // edge, and an edge of a cell is at most √3·h long.
  CHECK(worstNew <= 1e-4 * h);
  CHECK(report.maxAbsF == doctest::Approx(worstNew).epsilon(1e-6).scale(1e-300));
  const double before = worstCentroidGap(mesh, field), after = worstCentroidGap(refined, field);
  CAPTURE(before);
  CAPTURE(after);
  CHECK(after < before);
  CHECK(after <= 1.5 * options.tolerance);  // 4/3 for an exactly quadratic surface, plus higher orders
}

}  // namespace

TEST_CASE("chord refinement: a sphere's chords move onto it, closed and oriented") {
  const SphereField sphere(Vec<3>(0.05, -0.03, 0.02), 1.0);
  for (int resolution : {10, 24}) {
    CAPTURE(resolution);
    const TriMesh mesh = marchingCubes(sphere, cube(1.3), {resolution, 6});
    checkRefinement(sphere, mesh, 2.6 / resolution, 2);
  }
}

TEST_CASE("chord refinement: a torus (saddles bulge the other way) stays closed with Euler characteristic 0") {
  const TorusField torus;
  const TriMesh mesh = marchingCubes(torus, cube(1.1), {32, 6});
  checkRefinement(torus, mesh, 2.2 / 32, 0);
}

TEST_CASE("chord refinement: off (tolerance 0) or without normals the mesh is unchanged") {
  const SphereField sphere;
  TriMesh mesh = marchingCubes(sphere, cube(1.3), {12});
  ChordRefinementReport report;
  const TriMesh same = refineChords(mesh, sphere, {}, &report);
  CHECK(same.vertices == mesh.vertices);
  CHECK(same.triangles == mesh.triangles);
  CHECK(report.splitEdges == 0);
  mesh.normals.resize(3, 0);
  ChordRefinementOptions options;
  options.tolerance = 1e-6;
  const TriMesh bare = refineChords(mesh, sphere, options, &report);
  CHECK(bare.triangles == mesh.triangles);
  CHECK(report.splitEdges == 0);
}

TEST_CASE("chord refinement: an edge whose new vertex `rejects` stays whole, and the mesh stays closed") {
  const SphereField sphere;
  const TriMesh mesh = marchingCubes(sphere, cube(1.3), {16, 6});
  ChordRefinementOptions options;
  options.tolerance = 0.02 * 2.6 / 16;
  ChordRefinementReport all, some;
  const TriMesh full = refineChords(mesh, sphere, options, &all);
  options.rejects = [](const Points<3>& X) {
    std::vector<char> out(static_cast<std::size_t>(X.cols()));
    for (Eigen::Index k = 0; k < X.cols(); ++k) out[static_cast<std::size_t>(k)] = X(2, k) > 0.5;
    return out;
  };
  const TriMesh refined = refineChords(mesh, sphere, options, &some);
  CHECK(some.rejectedEdges > 0);
  CHECK(some.unsplitEdges == all.unsplitEdges + some.rejectedEdges);
  CHECK(some.splitEdges == all.splitEdges - some.rejectedEdges);
  const MeshCheck c = checkMesh(refined);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 2);
  CHECK(countFlippedTriangles(refined, refined.normals) == 0);
  int above = 0;
  for (int v = mesh.vertexCount(); v < refined.vertexCount(); ++v) above += refined.vertices(2, v) > 0.5;
  CHECK(above == 0);
  CHECK(full.vertexCount() == refined.vertexCount() + some.rejectedEdges);
}
