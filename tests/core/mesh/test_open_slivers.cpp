// Open slivers (open_slivers.h): open pieces smaller than the given area are left out with their
// vertices; closed pieces of any size, larger open pieces and a mesh of one piece stay.

#include <doctest/doctest.h>

#include <algorithm>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/open_slivers.h"
#include "core/mesh/tri_mesh.h"
#include "core/shapes/mesh_shapes.h"
#include "support/mesh_test_shapes.h"

using namespace hermite;
using hermite::testing::withPiece;

namespace {

TriMesh triangle(double size) {
  TriMesh t;
  t.vertices.resize(3, 3);
  t.vertices << 0, size, 0, 0, 0, size, 0, 0, 0;
  t.triangles.resize(3, 1);
  t.triangles << 0, 1, 2;
  return t;
}

// A ball of radius 0.5 and a bubble of radius 0.01 around the grid point (0.8125, 0, 0) of the
// 32-cell grid over [−1, 1]³ (cells 0.0625), with no data from x = 0.84 on: the bubble's piece
// is cut open and is far smaller than a cell face.
class BallAndCutBubble : public ImplicitField<3> {
 public:
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const Vec<3> c(0.8125, 0, 0);
    const double ball = x.norm() - 0.5, bubble = (x - c).norm() - 0.01;
    if (g) *g = ball < bubble ? x.normalized() : (x - c).normalized();
    if (H) H->setZero();
    return std::min(ball, bubble);
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }
  bool valid(const Vec<3>& x) const override { return x.x() < 0.84; }
  bool everywhereValid() const override { return false; }
};

}  // namespace

TEST_CASE("marching cubes leaves out an open piece smaller than a cell face and says so") {
  const BallAndCutBubble field;
  MarchingOptions options;
  options.resolution = 32;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, Box<3>{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)}, options, &r);
  CHECK(r.droppedSlivers == 1);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(mesh.vertices.row(0).maxCoeff() < 0.6);
}

TEST_CASE("open slivers: tiny open pieces go, closed pieces and larger open ones stay") {
  TriMesh sphere = uvSphereMesh(24, 12);
  sphere.normals.resize(3, 0);
  TriMesh tinyBall = uvSphereMesh(6, 4);
  tinyBall.vertices *= 0.01;  // closed, area ≈ 1.2e-3
  TriMesh mesh = withPiece(sphere, triangle(0.01), Vec<3>(3, 0, 0));  // open, area 5e-5
  mesh = withPiece(mesh, tinyBall, Vec<3>(-3, 0, 0));
  mesh = withPiece(mesh, triangle(1.0), Vec<3>(0, 3, 0));  // open, area 0.5
  REQUIRE(connectedComponentCount(mesh) == 4);
  const int vertices = mesh.vertexCount();
  CHECK(dropOpenSlivers(mesh, 1e-3) == 1);
  CHECK(connectedComponentCount(mesh) == 3);
  CHECK(mesh.vertexCount() == vertices - 3);
  CHECK(mesh.triangleCount() == sphere.triangleCount() + tinyBall.triangleCount() + 1);
  CHECK(mesh.vertices.row(0).maxCoeff() < 2.0);  // the tiny triangle at x = 3 is gone
  CHECK(dropOpenSlivers(mesh, 1e-3) == 0);
  CHECK(dropOpenSlivers(mesh, 1.0) == 1);  // now the larger open triangle too; the closed ball stays
  CHECK(connectedComponentCount(mesh) == 2);
}

TEST_CASE("open slivers: a mesh of one open piece is never dropped") {
  TriMesh t = triangle(0.001);
  CHECK(dropOpenSlivers(t, 1.0) == 0);
  CHECK(t.triangleCount() == 1);
}
