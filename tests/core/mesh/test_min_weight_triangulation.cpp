// The minimum-weight fallback of hole filling: the boundary triangulation, its refinement, and
// whole fills through it.

#include <doctest/doctest.h>

#include <cmath>
#include <map>

#include "core/mesh/hole_fill.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/min_weight_triangulation.h"
#include "core/shapes/analytic_shapes.h"
#include "support/mesh_test_shapes.h"

using namespace hermite;
using hermite::testing::cutBall;
using hermite::testing::parametricTorus;
using hermite::testing::smallestAngleDegrees;

namespace {

TriMesh sphereMesh(int resolution) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-1.3);
  b.hi = Vec<3>::Constant(1.3);
  return marchingCubes(SphereField{}, b, {resolution});
}

// Every directed boundary edge a → b of the loop is traversed b → a by exactly one triangle, and
// no other edge is used by the triangles more than once in either direction.
void checkClosesLoop(const BoundaryLoop& loop, const Eigen::Matrix3Xi& triangles) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    for (int c = 0; c < 3; ++c) ++directed[{triangles(c, t), triangles((c + 1) % 3, t)}];
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    const auto across = directed.find({b, a});
    CHECK((across != directed.end() && across->second == 1));
    CHECK(directed.count({a, b}) == 0);
  }
  for (const auto& [edge, count] : directed) CHECK(count == 1);
}

TriMesh withTriangles(const TriMesh& mesh, const Eigen::Matrix3Xi& added) {
  TriMesh out = mesh;
  out.triangles.conservativeResize(3, mesh.triangles.cols() + added.cols());
  out.triangles.rightCols(added.cols()) = added;
  return out;
}

}  // namespace

TEST_CASE("min-weight triangulation: n − 2 triangles that close the loop, oriented like the mesh") {
  const TriMesh closed = sphereMesh(40);
  for (double radius : {0.3, 0.9}) {  // the larger hole has more than 96 edges: cut into pieces first
    CAPTURE(radius);
    const TriMesh holed = cutBall(closed, Vec<3>(0, 0, 1), radius);
    const PreparedMesh prepared(holed);
    const std::vector<BoundaryLoop> loops = detectHoles(holed);
    REQUIRE(loops.size() == 1);
    CAPTURE(loops[0].size());
    double dihedral = -1;
    const Eigen::Matrix3Xi triangles = minWeightTriangulation(prepared, loops[0], 96, &dihedral);
    CHECK(triangles.cols() == Eigen::Index(loops[0].size()) - 2);
    CHECK(dihedral >= 0);
    CHECK(medianBoundaryDihedral(prepared, loops[0], triangles) < kRimDihedral);
    checkClosesLoop(loops[0], triangles);
    const MeshCheck c = checkMesh(withTriangles(holed, triangles));
    CHECK(c.closed());
    CHECK(c.edgeManifold());
    CHECK(c.consistentlyOriented());
    CHECK(c.eulerCharacteristic == 2);
  }
}

TEST_CASE("min-weight patch: refined to the boundary's edge length, closed, no angle below 1°") {
  const TriMesh holed = cutBall(sphereMesh(40), Vec<3>(0, 0, 1), 0.8);
  const PreparedMesh prepared(holed);
  const std::vector<BoundaryLoop> loops = detectHoles(holed);
  REQUIRE(loops.size() == 1);
  double lastProgress = -1;
  const HolePatch patch = minWeightPatch(prepared, loops[0], [&](double f) {
    CHECK(f >= lastProgress);
    lastProgress = f;
    return true;
  });
  REQUIRE(patch.closed);
  CHECK(lastProgress > 0);
  CHECK(patch.vertices.cols() > 0);  // refinement added interior vertices
  const TriMesh filled = appendPatches(holed, {&patch});
  const MeshCheck c = checkMesh(filled);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 2);
  double longest = 0;
  for (int t = holed.triangleCount(); t < filled.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (filled.vertices.col(filled.triangles(k, t)) -
                                   filled.vertices.col(filled.triangles((k + 1) % 3, t))).norm());
  CHECK(longest <= 2.0 * patch.meanEdgeLength);
  CHECK(smallestAngleDegrees(filled, holed.triangleCount()) >= 1.0);
  // Cancelling stops at once with the patch not closed.
  const HolePatch cancelled = minWeightPatch(prepared, loops[0], [](double) { return false; });
  CHECK_FALSE(cancelled.closed);
}

TEST_CASE("hole filling through the minimum-weight path: sphere and torus holes close as manifolds") {
  HoleFillOptions o;
  o.frontMaxEdges = 0;  // every hole goes to the fallback
  SUBCASE("sphere, three holes") {
    TriMesh holed = sphereMesh(36);
    for (const Vec<3>& c : {Vec<3>(0, 0, 1), Vec<3>(1, 0, 0), Vec<3>(0, -1, 0)}) holed = cutBall(holed, c, 0.35);
    const HoleFillResult r = fillHoles(holed, o);
    CHECK(r.holesFound == 3);
    CHECK(r.holesFilled == 3);
    for (const HoleReport& h : r.holes) CHECK(h.method == "min-weight");
    const MeshCheck c = checkMesh(r.mesh);
    CHECK(c.closedManifold());
    CHECK(c.eulerCharacteristic == 2);
    CHECK(smallestAngleDegrees(r.mesh, holed.triangleCount()) >= 1.0);
    CHECK(r.maxAbsF < 1e-3);  // projected onto the implicit
  }
  SUBCASE("torus: genus 1 kept") {
    const TriMesh holed = cutBall(parametricTorus(64, 32), Vec<3>(0.7, 0, 0.3), 0.25);
    const HoleFillResult r = fillHoles(holed, o);
    CHECK(r.holesFound == 1);
    CHECK(r.holesFilled == 1);
    const MeshCheck c = checkMesh(r.mesh);
    CHECK(c.closedManifold());
    CHECK(c.eulerCharacteristic == 0);
  }
}
