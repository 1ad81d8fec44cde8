// Cut-off tips (cut_tips.h): a small piece beside the largest one with a sample the grid misses
// between them is left out; without that sample, farther off, or larger, it stays. Through
// marching cubes: a ball whose tip hangs on a rod thinner than any grid's spacing comes out as
// one piece when the rod's samples are anchors, without a refined pass, and as two without them.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/mesh/cut_tips.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "core/shapes/mesh_shapes.h"
#include "support/mesh_test_shapes.h"

using namespace hermite;
using hermite::testing::withPiece;

namespace {

// A unit sphere (about 9 000 triangles) and a ball of radius 0.05 (48 triangles, under
// kTipShare of them) whose nearest vertex is `gap` from the sphere along +x.
TriMesh sphereAndBead(double gap, double beadRadius = 0.05, int beadRings = 4) {
  TriMesh sphere = uvSphereMesh(96, 48);
  TriMesh bead = uvSphereMesh(2 * beadRings, beadRings);
  bead.vertices *= beadRadius;
  return withPiece(sphere, bead, Vec<3>(1 + gap + beadRadius, 0, 0));
}

Points<3> pointsAt(const std::vector<Vec<3>>& at) {
  Points<3> P(3, static_cast<Eigen::Index>(at.size()));
  for (size_t i = 0; i < at.size(); ++i) P.col(static_cast<Eigen::Index>(i)) = at[i];
  return P;
}

}  // namespace

TEST_CASE("cut tips: a small piece beside the largest with a missed sample between them goes") {
  TriMesh mesh = sphereAndBead(0.05);
  REQUIRE(connectedComponentCount(mesh) == 2);
  const int sphereTriangles = mesh.triangleCount() - 48;
  CHECK(dropCutTips(mesh, pointsAt({Vec<3>(1.02, 0, 0)}), 0.1) == 1);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(mesh.triangleCount() == sphereTriangles);
  CHECK(mesh.vertices.row(0).maxCoeff() <= 1.0 + 1e-12);  // the bead's vertices went too
}

TEST_CASE("cut tips: without a missed sample beside it, farther off or larger, a piece stays") {
  SUBCASE("no missed sample") {
    TriMesh mesh = sphereAndBead(0.05);
    CHECK(dropCutTips(mesh, Points<3>(3, 0), 0.1) == 0);
    CHECK(dropCutTips(mesh, pointsAt({Vec<3>(-1.02, 0, 0)}), 0.1) == 0);  // beside the sphere only
    CHECK(connectedComponentCount(mesh) == 2);
  }
  SUBCASE("more than a cell diagonal from the largest piece") {
    TriMesh mesh = sphereAndBead(0.15);
    CHECK(dropCutTips(mesh, pointsAt({Vec<3>(1.1, 0, 0)}), 0.1) == 0);
    CHECK(connectedComponentCount(mesh) == 2);
  }
  SUBCASE("more than kTipShare of the triangles") {
    TriMesh mesh = sphereAndBead(0.05, 0.05, 16);  // 16 rings: 480 triangles
    CHECK(dropCutTips(mesh, pointsAt({Vec<3>(1.02, 0, 0)}), 0.1) == 0);
    CHECK(connectedComponentCount(mesh) == 2);
  }
}

namespace {

// The signed distance to a ball of radius 0.49 at the origin, a bead of radius 0.06 about the
// grid point (0.625, 0.0625, 0.0625) of the 32-cell grid over [−1, 1]³ (cells 0.0625), and a rod
// of radius 0.008 along x at y = z = kRod from inside the ball into the bead. The cells between
// x = 0.5 and 0.5625 about the rod have no sign change: samples on the rod there are missed.
// kRod lies midway between the lines of the grid refined there (quarters, 0.015625 apart), so
// neither grid has a point inside the rod, while the probes of marching_anchors.h (a cell
// diagonal in 8 steps) land inside it. The ball's and the bead's vertices are less than a cell
// diagonal apart.
constexpr double kRod = 0.0390625;
const Vec<3> kBead(0.625, 0.0625, 0.0625);

class BallRodBead : public ImplicitField<3> {
 public:
  // With `moon`, also a ball of radius 0.15 at (0, −0.8, 0): a piece of its own that is no tip.
  explicit BallRodBead(bool moon = false) : moon_(moon) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const Vec<3> onRod(std::clamp(x.x(), 0.45, 0.625), kRod, kRod), moon(0, -0.8, 0);
    double best = x.norm() - 0.49;
    Vec<3> dir = x.normalized();
    if (moon_ && (x - moon).norm() - 0.15 < best) best = (x - moon).norm() - 0.15, dir = (x - moon).normalized();
    if ((x - kBead).norm() - 0.06 < best) best = (x - kBead).norm() - 0.06, dir = (x - kBead).normalized();
    if ((x - onRod).norm() - 0.008 < best) best = (x - onRod).norm() - 0.008, dir = (x - onRod).normalized();
    if (g) *g = dir;
    if (H) H->setZero();
    return best;
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

 private:
  bool moon_;
};

// Points of the rod's surface outside the ball and the bead: 8 about each of 15 points of its axis.
Points<3> rodSamples(const ImplicitField<3>& f) {
  std::vector<Vec<3>> at;
  for (int i = 0; i < 15; ++i)
    for (int k = 0; k < 8; ++k) {
      const double phi = 2 * M_PI * k / 8;
      const Vec<3> q(0.49 + 0.005 * i, kRod + 0.008 * std::cos(phi), kRod + 0.008 * std::sin(phi));
      if (std::abs(f.evaluate(q)) < 1e-12) at.push_back(q);
    }
  return pointsAt(at);
}

}  // namespace

TEST_CASE("marching cubes: a tip the grid cuts off a rod thinner than a cell is left out beside missed samples") {
  const BallRodBead field;
  const Box<3> box{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)};
  MarchingOptions options;
  options.resolution = 32;
  MarchingReport plain;
  const TriMesh uniform = marchingCubes(field, box, options, &plain);
  REQUIRE(connectedComponentCount(uniform) == 2);  // the ball and the bead: the grid steps over the rod
  CHECK(plain.droppedTips == 0);                    // no anchors, no evidence of a neck
  const Points<3> anchors = rodSamples(field);
  REQUIRE(anchors.cols() > 20);
  options.anchors = &anchors;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, box, options, &r);
  CHECK(r.missedAnchors > 0);
  // The bead is a cut-off tip, so no refined pass is tried: the mesh is one piece without it.
  CHECK(r.refinement == MarchingReport::Refinement::OnePiece);
  CHECK(r.refinedCells[0] == 0);
  CHECK(r.droppedTips == 1);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(mesh.vertices.row(0).maxCoeff() < 0.5);
}

TEST_CASE("marching cubes: a refined pass runs for a piece that is no tip, and the tip still goes") {
  const BallRodBead field(true);
  const Box<3> box{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)};
  MarchingOptions options;
  options.resolution = 32;
  REQUIRE(connectedComponentCount(marchingCubes(field, box, options)) == 3);
  const Points<3> anchors = rodSamples(field);
  options.anchors = &anchors;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, box, options, &r);
  CHECK(r.refinement == MarchingReport::Refinement::NoGain);  // no refined grid point lies in the rod either
  CHECK(r.droppedTips == 1);
  CHECK(connectedComponentCount(mesh) == 2);  // the ball and the moon
  CHECK(mesh.vertices.row(0).maxCoeff() < 0.5);
}
