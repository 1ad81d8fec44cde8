#include <doctest/doctest.h>

#include <cmath>

#include "core/mesh/tri_mesh.h"
#include "support/mesh_test_shapes.h"

using namespace hermite;
using hermite::testing::cutBall;
using hermite::testing::parametricTorus;
using hermite::testing::removeTriangles;

namespace {

// A regular octahedron, counter-clockwise from outside.
TriMesh octahedron() {
  TriMesh m;
  m.vertices.resize(3, 6);
  m.vertices << 1, -1, 0, 0, 0, 0,  //
      0, 0, 1, -1, 0, 0,            //
      0, 0, 0, 0, 1, -1;
  m.triangles.resize(3, 8);
  m.triangles << 0, 2, 1, 3, 2, 0, 3, 1,  //
      2, 1, 3, 0, 0, 3, 1, 2,             //
      4, 4, 4, 4, 5, 5, 5, 5;
  // Rows above are (a, b, c) per column: top (0,2,4), (2,1,4), (1,3,4), (3,0,4); bottom (2,0,5), (0,3,5), (3,1,5), (1,2,5).
  return m;
}

}  // namespace

TEST_CASE("tri mesh: an octahedron is a closed oriented manifold") {
  const TriMesh m = octahedron();
  const MeshCheck c = checkMesh(m);
  CHECK(c.closedManifold());
  CHECK(c.edgeCount == 12);
  CHECK(c.eulerCharacteristic == 2);
  CHECK(c.components == 1);
  CHECK(signedVolume(m) == doctest::Approx(4.0 / 3.0));
  const Eigen::Matrix3Xd n = vertexNormals(m);
  for (int v = 0; v < 6; ++v) CHECK(n.col(v).dot(m.vertices.col(v)) == doctest::Approx(1.0));
  const Eigen::Matrix3Xd na = vertexNormals(m, NormalWeighting::Angle);
  CHECK((na - n).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK(countFlippedTriangles(m, n) == 0);
}

TEST_CASE("tri mesh: checks find flipped, non-manifold and degenerate triangles") {
  TriMesh m = octahedron();
  std::swap(m.triangles(0, 0), m.triangles(1, 0));  // flip one face
  MeshCheck c = checkMesh(m);
  CHECK(c.closed());
  CHECK(c.inconsistentEdges == 3);
  CHECK_FALSE(c.consistentlyOriented());

  TriMesh fin = octahedron();  // a fin: a third triangle on edge (0, 2)
  fin.vertices.conservativeResize(3, 7);
  fin.vertices.col(6) = Eigen::Vector3d(2, 2, 0);
  fin.triangles.conservativeResize(3, 9);
  fin.triangles.col(8) = Eigen::Vector3i(0, 6, 2);
  c = checkMesh(fin);
  CHECK(c.nonManifoldEdges == 1);
  CHECK(c.boundaryEdges == 2);

  TriMesh degenerate = octahedron();
  degenerate.vertices.col(4) = 0.5 * (degenerate.vertices.col(0) + degenerate.vertices.col(2));
  c = checkMesh(degenerate);
  CHECK(c.degenerateTriangles == 1);
}

TEST_CASE("tri mesh: boundary loops are ordered, oriented with the triangles and simple") {
  const TriMesh torus = parametricTorus(24, 12);
  CHECK(checkMesh(torus).closedManifold());
  CHECK(checkMesh(torus).eulerCharacteristic == 0);
  const TriMesh holed = cutBall(cutBall(torus, Eigen::Vector3d(1.0, 0, 0), 0.2), Eigen::Vector3d(-0.4, 0, 0), 0.15);
  const std::vector<BoundaryLoop> loops = boundaryLoops(holed);
  REQUIRE(loops.size() == 2);
  CHECK(checkMesh(holed).boundaryEdges == static_cast<int>(loops[0].size() + loops[1].size()));
  for (const BoundaryLoop& loop : loops) {
    // Each (vᵢ, vᵢ₊₁) is an edge of a triangle in that triangle's own order.
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      int uses = 0;
      for (int t = 0; t < holed.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k) uses += holed.triangles(k, t) == a && holed.triangles((k + 1) % 3, t) == b;
      CHECK(uses == 1);
    }
  }
  // Two holes touching at one vertex (a figure-eight): split into two simple loops.
  const int centre = 5 * 12 + 3;
  std::vector<int> fan;
  for (int t = 0; t < torus.triangleCount(); ++t)
    if ((torus.triangles.col(t).array() == centre).any()) fan.push_back(t);
  REQUIRE(fan.size() == 6);
  // Two of the six triangles around `centre` that share only that vertex.
  int second = -1;
  for (size_t k = 1; k < fan.size() && second < 0; ++k) {
    int shared = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) shared += torus.triangles(a, fan[0]) == torus.triangles(b, fan[k]);
    if (shared == 1) second = fan[k];
  }
  REQUIRE(second >= 0);
  const TriMesh eight = removeTriangles(torus, [&](int t) { return t == fan[0] || t == second; });
  const std::vector<BoundaryLoop> eightLoops = boundaryLoops(eight);
  REQUIRE(eightLoops.size() == 2);
  CHECK(eightLoops[0].size() == 3);
  CHECK(eightLoops[1].size() == 3);
}

TEST_CASE("tri mesh: connected components") {
  TriMesh two = octahedron();
  const TriMesh one = octahedron();
  two.vertices.conservativeResize(3, 12);
  two.vertices.rightCols(6) = one.vertices.array() + 5.0;
  two.triangles.conservativeResize(3, 16);
  two.triangles.rightCols(8) = one.triangles.array() + 6;
  int count = 0;
  const std::vector<int> label = triangleComponents(two, &count);
  CHECK(count == 2);
  CHECK(label[0] == 0);
  CHECK(label[15] == 1);
  CHECK(checkMesh(two).eulerCharacteristic == 4);
  // The vertex union-find finds the same pieces, numbered the same way (by first triangle).
  int byVertex = 0;
  CHECK(vertexConnectedComponents(two, &byVertex) == label);
  CHECK(byVertex == 2);
  CHECK(vertexConnectedComponentCount(two) == 2);
}
