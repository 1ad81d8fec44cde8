// Contouring without stray pockets (stray_pockets.h, winding_guard_field.h): pieces of a contour
// that lie inside or outside the samples' surface by their winding number are left out, a pocket
// joined to the surface is contoured again with the winding number's side, and true pieces,
// fields without no-data regions and sparse samples are left alone.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/stray_pockets.h"
#include "core/mesh/tri_mesh.h"
#include "core/mesh/winding_guard_field.h"
#include "core/shapes/presets.h"
#include "support/triangle_set.h"

using namespace hermite;

namespace {

const Box<3> kBox{Vec<3>::Constant(-1.6), Vec<3>::Constant(1.6)};

// A ball's signed distance with extra pieces: f = min(ball, blobs…) then max(·, −voids…)
// (a void is a ball of "outside" carved from the solid), optionally a tunnel from a void to the
// surface. Valid everywhere, but says it is not (as a partition of unity does), so that the
// stray check applies.
class BallWithExtras : public ImplicitField<3> {
 public:
  struct Ball {
    Vec<3> c;
    double r;
  };
  double radius = 1.0;  // the ball's, about the origin
  std::vector<Ball> blobs, voids;
  bool tunnel = false;  // a tube of radius 0.1 along +x from the first void to the surface
  bool claimsNoData = true;

  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    double f = x.norm() - radius;
    Vec<3> grad = x.normalized();
    for (const Ball& b : blobs) take(std::min(f, (x - b.c).norm() - b.r), (x - b.c).normalized(), f, grad, false);
    for (const Ball& b : voids) take(b.r - (x - b.c).norm(), -(x - b.c).normalized(), f, grad, true);
    if (tunnel && !voids.empty() && x.x() > voids[0].c.x()) {
      const Vec<3> radial(0, x.y() - voids[0].c.y(), x.z() - voids[0].c.z());
      take(0.1 - radial.norm(), -radial.normalized(), f, grad, true);
    }
    if (g) *g = grad;
    if (H) H->setZero();
    return f;
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }
  bool everywhereValid() const override { return !claimsNoData; }

 private:
  // f ← min(f, v) (a union) or max(f, v) (carving), with the gradient of the winner.
  static void take(double v, const Vec<3>& gv, double& f, Vec<3>& grad, bool carve) {
    if (carve ? v > f : v < f) f = v, grad = gv;
  }
};

HermiteSamples<3> sphereSamples() { return makePreset3d("sphere", 6000); }

MarchingOptions grid(int resolution) {
  MarchingOptions o;
  o.resolution = resolution;
  return o;
}

// The largest |‖v‖ − 1| over the mesh's vertices: how far it strays from the unit sphere.
double maxOffSphere(const TriMesh& mesh) {
  return (mesh.vertices.colwise().norm().array() - 1.0).abs().maxCoeff();
}

}  // namespace

TEST_CASE("stray pockets: a void inside and a blob outside are left out; the sphere stays") {
  BallWithExtras f;
  f.voids = {{Vec<3>(0.2, 0.1, 0), 0.15}};  // each about 2 % of the sphere's area
  f.blobs = {{Vec<3>(1.35, 0, 0.3), 0.15}};
  REQUIRE(connectedComponentCount(marchingCubes(f, kBox, grid(48))) == 3);
  StrayReport stray;
  const TriMesh mesh = contourWithoutStrays(f, kBox, grid(48), sphereSamples(), nullptr, &stray, nullptr);
  CHECK(stray.droppedPieces == 2);
  CHECK(stray.rounds == 0);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(maxOffSphere(mesh) < 0.01);
}

TEST_CASE("stray pockets: a void joined to the surface by a tunnel is contoured away with the winding number") {
  // A ball of radius 3 sampled about 0.05 apart; a void of radius 0.25 whose centre lies 0.6
  // inside, joined to the surface by a tube: under 1 % of the mesh, as a stray pocket is.
  BallWithExtras f;
  f.radius = 3;
  f.voids = {{Vec<3>(2.4, 0, 0), 0.25}};
  f.tunnel = true;
  HermiteSamples<3> samples = makePreset3d("sphere", 45000);
  samples.points *= 3.0;
  const Box<3> box{Vec<3>::Constant(-3.3), Vec<3>::Constant(3.3)};
  const auto deepest = [&](const TriMesh& m) {
    return (3.0 - m.vertices.colwise().norm().array()).maxCoeff();
  };
  const TriMesh plain = marchingCubes(f, box, grid(132));
  REQUIRE(connectedComponentCount(plain) == 1);
  REQUIRE(deepest(plain) > 0.8);  // the void's far side, 0.85 inside
  StrayReport stray;
  std::unique_ptr<ImplicitField<3>> guarded;
  const TriMesh mesh = contourWithoutStrays(f, box, grid(132), samples, nullptr, &stray, &guarded);
  CHECK(stray.strayVertices > 0);
  CHECK_FALSE(stray.tooMany);
  CHECK(stray.rounds >= 1);
  REQUIRE(guarded != nullptr);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  // What is left of the tunnel lies within three spacings of the samples, where the winding
  // number does not decide (0.048 when written).
  CHECK(deepest(mesh) < 0.15);
  // The guard turns f's sign inside the void and nowhere near the surface.
  CHECK(guarded->evaluate(Vec<3>(2.4, 0.1, 0)) < 0);
  CHECK(guarded->evaluate(Vec<3>(0, 0, 3.2)) == f.evaluate(Vec<3>(0, 0, 3.2)));
  // Only the cells about the strays were contoured again (contour_patch.h), and the result is the
  // whole grid's contour of the guarded field but for the remnants of the void (small pieces
  // inside the solid, left out).
  TriMesh full = marchingCubes(*guarded, box, grid(132));
  int pieces = 0;
  const std::vector<int> piece = vertexConnectedComponents(full, &pieces);
  std::vector<char> remnant(static_cast<size_t>(pieces), 1);
  remnant[static_cast<size_t>(piece[0])] = 0;  // the sphere's (its first triangle is on it)
  CHECK(dropComponents(full, piece, remnant) == stray.droppedPieces);
  CHECK(testing::triangleSet(mesh) == testing::triangleSet(full));
}

TEST_CASE("stray pockets: a second true piece stays") {
  // A second unit sphere beside the first, sampled too: the field is their union.
  BallWithExtras two;
  two.blobs = {{Vec<3>(2.5, 0, 0), 1.0}};
  const HermiteSamples<3> one = sphereSamples();
  HermiteSamples<3> both;
  both.points.resize(3, 2 * one.size());
  both.normals.resize(3, 2 * one.size());
  both.points << one.points, (one.points.colwise() + Vec<3>(2.5, 0, 0));
  both.normals << one.normals, one.normals;
  const Box<3> box{Vec<3>(-1.5, -1.5, -1.5), Vec<3>(4, 1.5, 1.5)};
  StrayReport stray;
  const TriMesh mesh = contourWithoutStrays(two, box, grid(64), both, nullptr, &stray, nullptr);
  CHECK(stray.droppedPieces == 0);
  CHECK(stray.rounds == 0);
  CHECK(connectedComponentCount(mesh) == 2);
}

TEST_CASE("stray pockets: fields without no-data regions and sparse samples are contoured as they are") {
  BallWithExtras f;
  f.voids = {{Vec<3>(0.2, 0.1, 0), 0.25}};
  const TriMesh plain = marchingCubes(f, kBox, grid(32));
  StrayReport stray;
  f.claimsNoData = false;
  TriMesh mesh = contourWithoutStrays(f, kBox, grid(32), sphereSamples(), nullptr, &stray, nullptr);
  CHECK(mesh.vertices == plain.vertices);
  CHECK(mesh.triangles == plain.triangles);
  f.claimsNoData = true;
  const HermiteSamples<3> sparse = makePreset3d("sphere", kGuardMinSamples - 1);
  mesh = contourWithoutStrays(f, kBox, grid(32), sparse, nullptr, &stray, nullptr);
  CHECK(mesh.triangles == plain.triangles);
  CHECK(stray.droppedPieces == 0);
}
