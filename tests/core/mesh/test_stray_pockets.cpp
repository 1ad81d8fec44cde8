// Contouring without stray pockets (stray_pockets.h, winding_guard_field.h): pieces of a contour
// that lie inside or outside the samples' surface by their winding number are left out, a pocket
// joined to the surface is contoured again with the winding number's side, a small piece beside
// the surface with a thin part's winding number goes as a cut-off tip, and true pieces, fields
// without no-data regions and sparse samples are left alone.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/mesh/occupied_cells.h"
#include "core/mesh/stray_pockets.h"
#include "core/mesh/tri_mesh.h"
#include "core/mesh/winding_guard_field.h"
#include "core/points/cloud_winding.h"
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

// The sphere's samples' spacing √(4π/N) (about 0.046 for sphereSamples()).
double sphereSpacing(const HermiteSamples<3>& samples) {
  return std::sqrt(4 * M_PI / static_cast<double>(samples.size()));
}

MarchingOptions grid(int resolution) {
  MarchingOptions o;
  o.resolution = resolution;
  return o;
}

// The largest |‖v‖ − 1| over the mesh's vertices: how far it strays from the unit sphere.
double maxOffSphere(const TriMesh& mesh) {
  return (mesh.vertices.colwise().norm().array() - 1.0).abs().maxCoeff();
}

// The mesh is the unit sphere alone: one closed piece, within 0.01 of it.
void checkSphereAlone(const TriMesh& mesh) {
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(maxOffSphere(mesh) < 0.01);
}

// `samples` with the columns of `points` and `normals` appended.
HermiteSamples<3> withSamples(HermiteSamples<3> samples, const Points<3>& points, const Points<3>& normals) {
  const Eigen::Index n = samples.size();
  samples.points.conservativeResize(3, n + points.cols());
  samples.normals.conservativeResize(3, n + points.cols());
  samples.points.rightCols(points.cols()) = points;
  samples.normals.rightCols(points.cols()) = normals;
  return samples;
}

// Two sheets of rows × rows samples each on a square grid of spacing h, interleaved: place(a, y,
// sheet) gives the sample and its normal at grid coordinates a = −(i + ½) h, y = (j − rows/2) h.
template <class Place>
HermiteSamples<3> twoSampledSheets(double h, int rows, Place&& place) {
  HermiteSamples<3> samples;
  samples.points.resize(3, 2 * rows * rows);
  samples.normals.resize(3, 2 * rows * rows);
  for (int i = 0, k = 0; i < rows; ++i)
    for (int j = 0; j < rows; ++j)
      for (int sheet = 0; sheet < 2; ++sheet, ++k) {
        const auto [point, normal] = place(-(i + 0.5) * h, (j - rows / 2) * h, sheet);
        samples.points.col(k) = point;
        samples.normals.col(k) = normal;
      }
  return samples;
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
  checkSphereAlone(mesh);
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
  const HermiteSamples<3> both = withSamples(one, one.points.colwise() + Vec<3>(2.5, 0, 0), one.normals);
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

namespace {

// The sphere's samples plus a fin of two sheets 0.04 apart (z = ±0.02, outward normals) over
// x ∈ [0.9, 1.3], y ∈ [−0.2, 0.2] at about the sphere's spacing: a part thinner than the
// samples' softening, whose winding number stays well below ½.
HermiteSamples<3> sphereAndFinSamples() {
  Points<3> p(3, 162), n(3, 162);
  Eigen::Index k = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (const double side : {-1.0, 1.0}) {
        p.col(k) = Vec<3>(0.9 + 0.05 * i, -0.2 + 0.05 * j, 0.02 * side);
        n.col(k++) = Vec<3>(0, 0, side);
      }
  return withSamples(sphereSamples(), p, n);
}

// The mean winding number of the mesh's vertices beyond x = 1.05 (the bead's).
double beadWinding(const TriMesh& mesh, const HermiteSamples<3>& samples) {
  const CloudWinding<3> winding(samples.points, samples.normals);
  double sum = 0;
  int count = 0;
  for (Eigen::Index v = 0; v < mesh.vertices.cols(); ++v)
    if (mesh.vertices(0, v) > 1.05) sum += winding.at(Vec<3>(mesh.vertices.col(v))), ++count;
  return count > 0 ? sum / count : -1;
}

}  // namespace

TEST_CASE("stray pockets: a small piece beside the surface with a thin part's winding number is a cut-off tip") {
  // The field is the ball and a bead of radius 0.045 at (1.12, 0.02, 0.01), 0.075 off the sphere
  // (a cell diagonal at 48³ is 0.115) and holding one grid point: the tip of the fin, cut off
  // from the body as a grid cuts a part thinner than a cell.
  BallWithExtras f;
  f.blobs = {{Vec<3>(1.12, 0.02, 0.01), 0.045}};
  const TriMesh plain = marchingCubes(f, kBox, grid(48));
  REQUIRE(connectedComponentCount(plain) == 2);
  const HermiteSamples<3> samples = sphereAndFinSamples();
  const double w = beadWinding(plain, samples);
  REQUIRE(w >= kPieceOutside);  // neither outside the samples' surface …
  REQUIRE(w < kTipWinding);     // … nor on it (½): a thin part's
  MarchingReport report;
  StrayReport stray;
  const TriMesh mesh = contourWithoutStrays(f, kBox, grid(48), samples, &report, &stray, nullptr);
  CHECK(report.droppedTips == 1);
  CHECK(stray.droppedPieces == 0);
  checkSphereAlone(mesh);
}

TEST_CASE("stray pockets: a small true piece beside the surface stays") {
  // A bead of radius 0.09, 0.07 off the sphere and sampled densely enough to close it (1000
  // samples, a fifth of the sphere's spacing): its winding number is about ½.
  const Vec<3> centre(1.16, 0.02, 0.01);
  BallWithExtras f;
  f.blobs = {{centre, 0.09}};
  const HermiteSamples<3> bead = makePreset3d("sphere", 1000);
  const HermiteSamples<3> samples =
      withSamples(sphereSamples(), (bead.points * 0.09).colwise() + centre, bead.normals);
  const TriMesh plain = marchingCubes(f, kBox, grid(48));
  REQUIRE(connectedComponentCount(plain) == 2);
  REQUIRE(beadWinding(plain, samples) >= kTipWinding);
  MarchingReport report;
  StrayReport stray;
  const TriMesh mesh = contourWithoutStrays(f, kBox, grid(48), samples, &report, &stray, nullptr);
  CHECK(report.droppedTips == 0);
  CHECK(stray.droppedPieces == 0);
  CHECK(connectedComponentCount(mesh) == 2);
}

TEST_CASE("stray pockets: a dent nearer the samples than the occupancy test sees is contoured away") {
  // A void of radius 0.28 centred 0.2 above the north pole: a crater 0.08 deep (1.7 sample
  // spacings of about 0.046) and 0.2 wide. On the 24³ grid the occupancy cells are 1.3 spacings,
  // so the rim's samples lie within the 3 × 3 × 3 cells about its floor: only the floor's
  // distance to the samples' tangent planes shows it.
  BallWithExtras f;
  f.voids = {{Vec<3>(0, 0, 1.2), 0.28}};
  const HermiteSamples<3> samples = sphereSamples();
  const TriMesh plain = marchingCubes(f, kBox, grid(24));
  REQUIRE(maxOffSphere(plain) > 0.06);
  const double spacing = sphereSpacing(samples);
  const OccupiedCells occupied(samples.points, kBox.lo, std::min(0.5 * 3.2 / 24, 1.3 * spacing));
  REQUIRE_FALSE(occupied.farFromSamples(Vec<3>(0, 0, 0.93)));
  StrayReport stray;
  const TriMesh mesh = contourWithoutStrays(f, kBox, grid(24), samples, nullptr, &stray, nullptr);
  CHECK(stray.strayVertices > 0);
  CHECK(stray.rounds >= 1);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(maxOffSphere(mesh) < 0.5 * maxOffSphere(plain));
}

TEST_CASE("stray pockets: the plane test for vertices added after the review") {
  // 6000 samples of the unit sphere: spacing √(4π / 6000) ≈ 0.046.
  const HermiteSamples<3> samples = sphereSamples();
  const double spacing = sphereSpacing(samples);
  const StrayTest stray(samples, kBox, 4 * M_PI);
  BallWithExtras ball;
  CHECK(StrayTest::appliesTo(ball, samples));
  ball.claimsNoData = false;
  CHECK_FALSE(StrayTest::appliesTo(ball, samples));
  // 40 directions between the samples' own (a golden-angle spiral of another count), each at 4
  // distances: on the surface, within the samples' reach, a blob outside (winding number about
  // 0), a dent inside (about 1).
  const double offsets[4] = {0.0, 0.3 * spacing, 2.0 * spacing, -2.0 * spacing};
  Points<3> X(3, 160);
  for (int i = 0; i < 40; ++i) {
    const double z = 1 - 2 * (i + 0.5) / 40, phi = 2.399963 * i;
    const Vec<3> u(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    for (int k = 0; k < 4; ++k) X.col(4 * i + k) = (1 + offsets[k]) * u;
  }
  // 80 strays: more than the 64 the direct sum serves, so the samples' winding number decides.
  const std::vector<char> strays = stray(X);
  int flagged[4] = {};
  for (int i = 0; i < 160; ++i) flagged[i % 4] += strays[static_cast<std::size_t>(i)];
  // The first 20 directions alone: 40 strays, decided by the direct sum.
  const std::vector<char> fewer = stray(X.leftCols(80));
  CHECK(std::equal(fewer.begin(), fewer.end(), strays.begin()));
  CHECK(flagged[0] == 0);
  CHECK(flagged[1] == 0);
  CHECK(flagged[2] == 40);
  CHECK(flagged[3] == 40);
}

TEST_CASE("stray pockets: a cap beyond the tip of a part thinner than the sampling is a stray") {
  // Two sheets 0.2 spacings apart (z = ±0.1 h, normals ±z) on a square grid of spacing h ending
  // at x = −h/2: a plate thinner than the sampling. Beyond its tip, in its mid-plane, the samples
  // of both sides put a point 0.1 h behind their planes on average, so only its distance tells.
  const double h = 0.01;
  const int rows = 40;
  const HermiteSamples<3> samples = twoSampledSheets(h, rows, [&](double a, double y, int sheet) {
    const double side = sheet == 0 ? 1.0 : -1.0;
    return std::pair{Vec<3>(a, y, 0.1 * h * side), Vec<3>(0, 0, side)};
  });
  const Box<3> box{Vec<3>(-0.5, -0.3, -0.1), Vec<3>(0.1, 0.3, 0.1)};
  const StrayTest stray(samples, box, 2 * (rows * h) * (rows * h));
  Points<3> X(3, 3);
  X.col(0) = Vec<3>(1.1 * h, 0.3 * h, 0);  // 1.6 h from the nearest sample, winding number about 0
  X.col(1) = Vec<3>(0.5 * h, 0.3 * h, 0);  // 1.0 h: within the samples' reach
  X.col(2) = Vec<3>(-3 * h, 0.3 * h, 0);   // in the plate
  const std::vector<char> s = stray(X);
  CHECK(s[0] == 1);
  CHECK(s[1] == 0);
  CHECK(s[2] == 0);
}

// Contours f — the sphere with a pocket 2.5 sample spacings deep or high — on a grid of about a
// spacing, with the stray review: the pocket must end within 0.4 spacings of the sampled sphere,
// in a closed mesh, after at least one guard round.
void checkPocketRepaired(const BallWithExtras& f, const HermiteSamples<3>& samples) {
  const double spacing = sphereSpacing(samples);
  const TriMesh plain = marchingCubes(f, kBox, grid(64));
  REQUIRE(maxOffSphere(plain) > 2 * spacing);
  StrayReport stray;
  const TriMesh mesh = contourWithoutStrays(f, kBox, grid(64), samples, nullptr, &stray, nullptr);
  CHECK(maxOffSphere(mesh) < 0.4 * spacing);
  CHECK(stray.rounds >= 1);
  CHECK(checkMesh(mesh).closedManifold());
}

TEST_CASE("stray pockets: a repaired dent ends within 0.4 spacings of the sampled surface") {
  // A crater: the guard fills it up to where the samples' winding number passes kGuardInside.
  // Filled up to w = 0.85 instead, the floor stays 0.51 spacings deep.
  const HermiteSamples<3> samples = sphereSamples();
  const double r = 0.3;
  BallWithExtras f;
  f.voids = {{Vec<3>(0, 0, 1 + r - 2.5 * sphereSpacing(samples)), r}};
  checkPocketRepaired(f, samples);
}

TEST_CASE("stray pockets: a repaired bulge ends within 0.4 spacings of the sampled surface") {
  // A blob standing out of the sphere: the guard cuts it down to where the samples' winding
  // number passes kGuardOutside. Cut down to w = 0.15 instead, the top stays 0.53 spacings high.
  const HermiteSamples<3> samples = sphereSamples();
  const double r = 0.15;
  BallWithExtras f;
  f.blobs = {{Vec<3>(0, 0, 1 - r + 2.5 * sphereSpacing(samples)), r}};
  checkPocketRepaired(f, samples);
}

TEST_CASE("stray pockets: beyond a hole in the sampling a winding number past the guard's level decides") {
  // The sphere's samples without those within 2 spacings of the north pole. 1.35 spacings below
  // the hole's centre the samples' winding number is about 0.8 (the missing disc takes about a
  // fifth of the solid angle), 1.2 above about 0.21: beyond kGuardInside and kGuardOutside, short
  // of 0.85 and 0.15, and the nearest sample is 2.4 spacings away (the plane test reaches 2.5):
  // strays, whose side the samples still tell (levels of 0.85 and 0.15 would call none).
  const HermiteSamples<3> all = sphereSamples();
  const double spacing = sphereSpacing(all);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < all.size(); ++i)
    if (std::acos(std::clamp(all.points(2, i), -1.0, 1.0)) > 2 * spacing) kept.push_back(i);
  HermiteSamples<3> samples;
  samples.points = all.points(Eigen::all, kept);
  samples.normals = all.normals(Eigen::all, kept);
  const StrayTest stray(samples, kBox, 4 * M_PI);
  // 40 points on a circle of 0.05 spacings about each place (80: more than the 64 the direct sum
  // serves, so the samples' winding number decides), and one on the sampled surface.
  Points<3> X(3, 81);
  for (int i = 0; i < 40; ++i) {
    const Vec<3> around(0.05 * spacing * std::cos(0.157 * i), 0.05 * spacing * std::sin(0.157 * i), 0);
    X.col(i) = around + Vec<3>(0, 0, 1 - 1.35 * spacing);
    X.col(40 + i) = around + Vec<3>(0, 0, 1 + 1.2 * spacing);
  }
  X.col(80) = Vec<3>(0, 0, -1);
  const std::vector<double> w = stray.winding()->at(X);
  const auto [inLo, inHi] = std::minmax_element(w.begin(), w.begin() + 40);
  const auto [outLo, outHi] = std::minmax_element(w.begin() + 40, w.begin() + 80);
  REQUIRE((*inLo > kGuardInside && *inHi < 0.85));
  REQUIRE((*outHi < kGuardOutside && *outLo > 0.15));
  const std::vector<char> s = stray(X);
  CHECK(std::count(s.begin(), s.begin() + 40, 1) == 40);
  CHECK(std::count(s.begin() + 40, s.begin() + 80, 1) == 40);
  CHECK(s[80] == 0);
}

TEST_CASE("stray pockets: a bulge a spacing high over a sample is a stray") {
  // 1.1 spacings straight over a sample of the sphere its nearest sample is that one (the next
  // are about 1.5 away), the samples' planes put it about a spacing off, and the winding number
  // is near 0; 0.9 spacings over one it is within the samples' reach.
  const HermiteSamples<3> samples = sphereSamples();
  const double spacing = sphereSpacing(samples);
  const StrayTest stray(samples, kBox, 4 * M_PI);
  Points<3> X(3, 40);
  for (int i = 0; i < 20; ++i) {
    const Vec<3> p = samples.points.col(150 * i + 75);
    X.col(i) = p + 1.1 * spacing * p.normalized();
    X.col(20 + i) = p + 0.9 * spacing * p.normalized();
  }
  const std::vector<char> s = stray(X);
  CHECK(std::count(s.begin(), s.begin() + 20, 1) == 20);
  CHECK(std::count(s.begin() + 20, s.end(), 1) == 0);
}

TEST_CASE("stray pockets: a bulge beside a convex edge is a stray though the mean plane hides it") {
  // The quarter space x ≤ 0, z ≤ 0 sampled on a square grid of spacing h: its top face (normal +z)
  // and its side face (normal +x) meet in a right-angled edge along y. A point 0.75 h over the top
  // face's plane and 1 h behind the side face's, over the middle of a grid cell: 1.03 h from the
  // nearest sample; the top's samples put it 0.75 h out, the side's 1 h in, on average under
  // half a spacing out.
  const double h = 0.01;
  const int rows = 40;
  const HermiteSamples<3> samples = twoSampledSheets(h, rows, [](double a, double y, int sheet) {
    return sheet == 0 ? std::pair{Vec<3>(a, y, 0), Vec<3>(0, 0, 1)} : std::pair{Vec<3>(0, y, a), Vec<3>(1, 0, 0)};
  });
  const Box<3> box{Vec<3>(-0.5, -0.3, -0.5), Vec<3>(0.1, 0.3, 0.1)};
  const StrayTest stray(samples, box, 2 * (rows * h) * (rows * h));
  Points<3> X(3, 2);
  X.col(0) = Vec<3>(-h, 0.5 * h, 0.75 * h);
  X.col(1) = Vec<3>(-h, 0.5 * h, 0);  // on the top face
  double sum = 0;
  int near = 0;
  for (Eigen::Index i = 0; i < samples.size(); ++i)
    if ((samples.points.col(i) - X.col(0)).norm() <= 2.5 * h) {
      sum += samples.normals.col(i).dot(X.col(0) - samples.points.col(i));
      ++near;
    }
  REQUIRE(near > 0);
  REQUIRE(sum / near < 0.5 * h);  // the mean alone would not call it far
  REQUIRE(stray.winding()->at(Vec<3>(X.col(0))) < kGuardOutside);
  const std::vector<char> s = stray(X);
  CHECK(s[0] == 1);
  CHECK(s[1] == 0);
}

TEST_CASE("stray pockets: strays up to 2 % of the vertices are still guarded") {
  // Two blobs standing 2.5 spacings out of the sampled sphere: their strays are more than 1 % of
  // the contour's vertices, far under the 7–9 % of a surface sampled too thinly to trust w.
  const HermiteSamples<3> samples = sphereSamples();
  const double r = 0.15, lift = 1 - r + 2.5 * sphereSpacing(samples);
  BallWithExtras f;
  f.blobs = {{Vec<3>(0, 0, lift), r}, {Vec<3>(0, 0, -lift), r}};
  StrayReport stray;
  const TriMesh plain = marchingCubes(f, kBox, grid(64));
  const TriMesh mesh = contourWithoutStrays(f, kBox, grid(64), samples, nullptr, &stray, nullptr);
  CHECK(stray.strayVertices > 0.01 * plain.vertexCount());  // about 1.4 %
  CHECK_FALSE(stray.tooMany);
  CHECK(maxOffSphere(mesh) < 0.4 * sphereSpacing(samples));
}
