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
#include "support/mesh_distance.h"
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

namespace {

// A unit sphere with a pocket of the outside inside it: a ball of radius 0.05 (48 triangles)
// turned inside out (negative signed volume), at the origin, far from the sphere.
TriMesh sphereAndPocket(bool inverted = true) {
  TriMesh bead = uvSphereMesh(8, 4);
  bead.vertices *= 0.05;
  if (inverted) bead.triangles.row(1).swap(bead.triangles.row(2));
  return withPiece(uvSphereMesh(96, 48), bead, Vec<3>::Zero());
}

}  // namespace

TEST_CASE("cut tips: a pocket of the outside with samples off the mesh beside it goes, however far from the largest") {
  // Samples on a crack's walls 0.25 from the pocket: more than kGapOff cell diagonals (0.1) from
  // every vertex, within kGapReach of the pocket's box.
  const Points<3> crack = pointsAt({Vec<3>(0.25, 0, 0.01), Vec<3>(0.25, 0, -0.01)});
  SUBCASE("goes") {
    TriMesh mesh = sphereAndPocket();
    int gaps = -1;
    CHECK(dropCutTips(mesh, Points<3>(3, 0), 0.1, &gaps, &crack) == 1);
    CHECK(gaps == 1);
    CHECK(connectedComponentCount(mesh) == 1);
    CHECK(mesh.vertices.colwise().norm().minCoeff() >= 1.0 - 1e-3);  // the pocket's vertices went too
  }
  SUBCASE("without the samples, or with them only on the pocket, it stays") {
    TriMesh mesh = sphereAndPocket();
    int gaps = -1;
    CHECK(dropCutTips(mesh, Points<3>(3, 0), 0.1, &gaps) == 0);
    const Points<3> onPocket = pointsAt({Vec<3>(0.05, 0, 0), Vec<3>(0, -0.05, 0)});
    CHECK(dropCutTips(mesh, Points<3>(3, 0), 0.1, &gaps, &onPocket) == 0);
    CHECK(gaps == 0);
    CHECK(connectedComponentCount(mesh) == 2);
  }
  SUBCASE("a small solid piece there is no pocket, and stays") {
    TriMesh mesh = sphereAndPocket(false);
    CHECK(dropCutTips(mesh, Points<3>(3, 0), 0.1, nullptr, &crack) == 0);
    CHECK(connectedComponentCount(mesh) == 2);
  }
  SUBCASE("farther samples are not its evidence") {
    TriMesh mesh = sphereAndPocket();
    const Points<3> far = pointsAt({Vec<3>(0.5, 0, 0)});  // beyond kGapReach cell diagonals of its box
    CHECK(dropCutTips(mesh, Points<3>(3, 0), 0.1, nullptr, &far) == 0);
    CHECK(connectedComponentCount(mesh) == 2);
  }
}

namespace {

// samplesOnPockets as the refined pass calls it: the candidates and what dropCutTips would leave out.
std::vector<int> onPockets(const TriMesh& mesh, const Points<3>& missed, double d, const Points<3>& samples) {
  const TipCandidates c = tipCandidates(mesh, d);
  return samplesOnPockets(mesh, c, cutTipsToDrop(mesh, c, missed, d, &samples), d, samples);
}

}  // namespace

TEST_CASE("cut tips: the samples on a pocket that goes are those within half a cell diagonal of it") {
  // The crack's two samples off the mesh, and three on or near the pocket (radius 0.05): at it,
  // 0.03 off it (within 0.05, half the cell diagonal 0.1) and 0.08 off it.
  const Points<3> samples = pointsAt({Vec<3>(0.25, 0, 0.01), Vec<3>(0.25, 0, -0.01), Vec<3>(0, 0, 0.05),
                                      Vec<3>(0.08, 0, 0), Vec<3>(0, -0.13, 0)});
  const TriMesh mesh = sphereAndPocket();
  CHECK(onPockets(mesh, Points<3>(3, 0), 0.1, samples) == std::vector<int>{2, 3});
  // Without the crack's samples the pocket is a cavity that stays, and no sample is on a pocket
  // that goes; nor on a small solid piece, which is no pocket.
  CHECK(onPockets(mesh, Points<3>(3, 0), 0.1, samples.rightCols(3)).empty());
  CHECK(onPockets(sphereAndPocket(false), Points<3>(3, 0), 0.1, samples).empty());
  // A missed sample beside it makes it go too.
  CHECK(onPockets(mesh, pointsAt({Vec<3>(0.1, 0, 0)}), 0.1, samples.rightCols(3)) == std::vector<int>{0, 1});
}

namespace {

// The signed distance (to first order) to a ball of radius 0.8 with a slot 0.01 wide cut into it
// from +x (|z − kSlot| < 0.005 for x > 0) and a bubble of radius 0.07 at the origin, at the slot's
// inner end. On the 32-cell grid over [−1, 1]³ (cells 0.0625) the slot lies between the point
// planes z = 0 and z = 0.0625, so the grid fills it, while the bubble holds grid points: it comes
// out as a pocket of the outside inside the ball.
constexpr double kSlot = 0.03125;

class SlottedBall : public ImplicitField<3> {
 public:
  explicit SlottedBall(bool slot) : slot_(slot) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    // The hollow: the union of the slot and the bubble; the solid: the ball minus the hollow.
    double hollow = x.norm() - 0.07;
    Vec<3> hollowDir = x.normalized();
    const double slab = std::abs(x.z() - kSlot) - 0.005;
    if (slot_ && std::max(slab, -x.x()) < hollow) {
      hollow = std::max(slab, -x.x());
      hollowDir = slab > -x.x() ? Vec<3>(0, 0, x.z() > kSlot ? 1 : -1) : Vec<3>(-1, 0, 0);
    }
    double f = x.norm() - 0.8;
    Vec<3> dir = x.normalized();
    if (-hollow > f) f = -hollow, dir = -hollowDir;
    if (g) *g = dir;
    if (H) H->setZero();
    return f;
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

 private:
  bool slot_;
};

// Points on the slot's two walls between the bubble and the ball's surface, at least `from` from
// the centre (off the bubble).
Points<3> slotWallSamples(double from = 0.09) {
  std::vector<Vec<3>> at;
  for (int i = 0; i < 12; ++i)
    for (int j = -3; j <= 3; ++j)
      for (double side : {-0.005, 0.005}) {
        const Vec<3> q(0.1 + 0.05 * i, 0.05 * j, kSlot + side);
        if (q.norm() < 0.78 && q.norm() > from) at.push_back(q);
      }
  return pointsAt(at);
}

}  // namespace

TEST_CASE("marching cubes: the pocket a grid keeps of a slot thinner than a cell is left out beside the slot's samples") {
  const Box<3> box{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)};
  MarchingOptions options;
  options.resolution = 32;
  const SlottedBall slotted(true);
  const TriMesh plain = marchingCubes(slotted, box, options);
  REQUIRE(connectedComponentCount(plain) == 2);  // the ball, and the bubble inside it
  // Samples on the slot's walls, none within half a cell diagonal of the bubble: it has no
  // samples of its own, so it goes without a refined pass.
  const Points<3> walls = slotWallSamples(0.2);
  REQUIRE(walls.cols() > 100);
  options.anchors = &walls;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(slotted, box, options, &r);
  CHECK(r.droppedGaps == 1);
  CHECK(r.droppedTips == 0);
  CHECK(r.refinedCells[0] == 0);  // no refined pass for a piece that goes anyway
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(mesh.vertices.colwise().norm().minCoeff() > 0.5);

  // A cavity with no slot: its own samples are on the mesh, so it stays, without a refined pass.
  const SlottedBall cavity(false);
  Points<3> onCavity(3, 6);
  for (int a = 0; a < 3; ++a) {
    onCavity.col(2 * a) = 0.07 * Vec<3>::Unit(a);
    onCavity.col(2 * a + 1) = -0.07 * Vec<3>::Unit(a);
  }
  options.anchors = &onCavity;
  MarchingReport rc;
  CHECK(connectedComponentCount(marchingCubes(cavity, box, options, &rc)) == 2);
  CHECK(rc.droppedGaps == 0);
  CHECK(rc.refinedCells[0] == 0);
}

TEST_CASE("marching cubes: a pocket with samples on its walls is joined to the surface by a refined grid") {
  // The slot's samples reach the bubble: those on the pocket would leave the mesh with it, so the
  // grid is refined about them, which opens the slot along its length (its z interval is cut in
  // kAnchorSplit everywhere) and joins the bubble to the ball's surface.
  const Box<3> box{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)};
  MarchingOptions options;
  options.resolution = 32;
  const Points<3> walls = slotWallSamples();
  options.anchors = &walls;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(SlottedBall(true), box, options, &r);
  CHECK(r.refinement == MarchingReport::Refinement::Refined);
  CHECK(r.refinedCells[2] > 32);
  CHECK(r.droppedGaps == 0);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(mesh.vertices.colwise().norm().minCoeff() < 0.08);  // the bubble's wall is kept
  // Every wall sample lies on the mesh, to within a refined step across the slot (0.0156; the
  // walls are planes the refined grid's cells cross, so the mesh is on them).
  CHECK(testing::farthestFromMesh(mesh, walls) < 2.0 / 32 / kAnchorSplit);
}
