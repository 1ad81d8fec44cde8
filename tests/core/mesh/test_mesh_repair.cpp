// What hole filling mends in its input before looking for holes (mesh_repair.h).

#include <doctest/doctest.h>

#include "core/mesh/hole_fill.h"
#include "core/mesh/mesh_repair.h"
#include "core/mesh/tri_mesh.h"
#include "support/mesh_test_shapes.h"

using namespace hermite;
using hermite::testing::parametricTorus;

namespace {

TriMesh withExtraTriangle(const TriMesh& mesh, const Eigen::Vector3i& triangle) {
  TriMesh out = mesh;
  out.triangles.conservativeResize(3, mesh.triangles.cols() + 1);
  out.triangles.col(mesh.triangles.cols()) = triangle;
  return out;
}

// A strip of `n` quads whose ends are glued with a half twist: one non-orientable component.
TriMesh moebius(int n) {
  TriMesh m;
  m.vertices.resize(3, 2 * n);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    for (int s = 0; s < 2; ++s) {
      const double w = (s == 0 ? -0.2 : 0.2);
      m.vertices.col(2 * k + s) = Vec<3>((1 + w * std::cos(a / 2)) * std::cos(a), (1 + w * std::cos(a / 2)) * std::sin(a),
                                         w * std::sin(a / 2));
    }
  }
  std::vector<Eigen::Vector3i> tris;
  for (int k = 0; k < n; ++k) {
    const int a0 = 2 * k, a1 = 2 * k + 1;
    const bool last = k == n - 1;
    const int b0 = last ? 1 : 2 * k + 2, b1 = last ? 0 : 2 * k + 3;  // the twist swaps the sides
    tris.emplace_back(a0, b0, b1);
    tris.emplace_back(a0, b1, a1);
  }
  m.triangles.resize(3, Eigen::Index(tris.size()));
  for (std::size_t t = 0; t < tris.size(); ++t) m.triangles.col(Eigen::Index(t)) = tris[t];
  return m;
}

}  // namespace

TEST_CASE("mesh repair: a clean mesh is returned unchanged") {
  const TriMesh torus = parametricTorus(24, 12);
  MeshRepairReport report;
  const TriMesh out = repairMesh(torus, report);
  CHECK(report.clean());
  CHECK(report.messages.empty());
  CHECK(out.triangles == torus.triangles);
}

TEST_CASE("mesh repair: duplicate faces are dropped, flipped faces turned back, coincident vertices welded") {
  const TriMesh torus = parametricTorus(24, 12);
  SUBCASE("duplicate face, in another vertex order") {
    const Eigen::Vector3i t0 = torus.triangles.col(5);
    MeshRepairReport report;
    const TriMesh out = repairMesh(withExtraTriangle(torus, Eigen::Vector3i(t0(1), t0(2), t0(0))), report);
    CHECK(report.duplicateFaces == 1);
    CHECK(out.triangleCount() == torus.triangleCount());
    CHECK(checkMesh(out).closedManifold());
  }
  SUBCASE("one flipped face") {
    TriMesh flipped = torus;
    std::swap(flipped.triangles(1, 7), flipped.triangles(2, 7));
    CHECK_FALSE(checkMesh(flipped).consistentlyOriented());
    MeshRepairReport report;
    const TriMesh out = repairMesh(flipped, report);
    CHECK(report.reorientedFaces == 1);
    CHECK(out.triangles == torus.triangles);
  }
  SUBCASE("a vertex duplicated at the same position: welded, the copy left unused") {
    TriMesh split = torus;
    const int v = split.triangles(0, 3);
    split.vertices.conservativeResize(3, split.vertices.cols() + 1);
    split.vertices.col(split.vertices.cols() - 1) = split.vertices.col(v);
    split.triangles(0, 3) = int(split.vertices.cols()) - 1;  // one triangle uses the copy: a seam
    CHECK_FALSE(checkMesh(split).closed());
    MeshRepairReport report;
    const TriMesh out = repairMesh(split, report);
    CHECK(report.weldedVertices == 1);
    CHECK(checkMesh(out).closedManifold());
  }
}

TEST_CASE("mesh repair: a Möbius strip is reported as non-orientable, never silently '0 holes'") {
  const TriMesh strip = moebius(24);
  MeshRepairReport report;
  repairMesh(strip, report);
  CHECK(report.nonOrientableComponents == 1);
  REQUIRE_FALSE(report.messages.empty());
  const HoleFillResult r = fillHoles(strip);
  bool said = false;
  for (const std::string& m : r.messages) said |= m.find("non-orientable") != std::string::npos;
  CHECK(said);
}
