// Marching cubes refined at anchors (MarchingOptions::anchors, marching_anchors.h): a neck
// thinner than a cell that the uniform grid steps over splits the mesh; with samples on the
// neck as anchors the grid is cut finer there and the mesh is one closed piece again. Fields
// without thin parts mesh exactly as without anchors, and a refinement that would not fit in
// memory is refused with its reason.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/base/memory_check.h"
#include "core/mesh/grid_lines.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/near_mesh_distance.h"
#include "core/mesh/tri_mesh.h"

using namespace hermite;

namespace {

const Box<3> kBox{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)};
// Rods run along x at y = z = kAxis. On the 32-cell grid over kBox (lines at multiples of 0.0625)
// that axis lies 0.044 from every grid line, so a rod of radius 0.02 holds no grid point.
constexpr double kAxis = 0.031;

struct Ball {
  Vec<3> centre;
  double radius;
};

// The signed distance to a union of balls and at most one rod (radius 0: none) along x from x0
// to x1 (1-Lipschitz).
class BallsAndRod : public ImplicitField<3> {
 public:
  BallsAndRod(std::vector<Ball> balls, double x0 = 0, double x1 = 0, double rod = 0)
      : balls_(std::move(balls)), x0_(x0), x1_(x1), rod_(rod) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    double best = 1e300;
    Vec<3> dir = Vec<3>::UnitX();
    const auto take = [&](const Vec<3>& p, double r) {
      const double d = (x - p).norm() - r;
      if (d < best) best = d, dir = (x - p).normalized();
    };
    for (const Ball& b : balls_) take(b.centre, b.radius);
    if (rod_ > 0) take(Vec<3>(std::clamp(x.x(), x0_, x1_), kAxis, kAxis), rod_);
    if (g) *g = dir;
    if (H) H->setZero();
    return best;
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

 private:
  std::vector<Ball> balls_;
  double x0_, x1_, rod_;
};

// Points of the field's zero set among 8 around each circle of radius r about (x, kAxis, kAxis)
// in the plane x = const, for x in xs: a rod's surface, or the equators of beads on the axis.
std::vector<Vec<3>> ringSamples(const ImplicitField<3>& f, const std::vector<double>& xs, double r) {
  std::vector<Vec<3>> p;
  for (double x : xs)
    for (int k = 0; k < 8; ++k) {
      const double t = 2 * M_PI * k / 8;
      const Vec<3> q(x, kAxis + r * std::cos(t), kAxis + r * std::sin(t));
      if (std::abs(f.evaluate(q)) < 1e-12) p.push_back(q);
    }
  return p;
}

// Points of the field's zero set among n on the sphere (centre c, radius r), a Fibonacci spiral.
std::vector<Vec<3>> sphereSamples(const ImplicitField<3>& f, const Vec<3>& c, double r, int n) {
  std::vector<Vec<3>> p;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2.0 * i + 1) / n, s = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
    const Vec<3> q = c + r * Vec<3>(s * std::cos(phi), s * std::sin(phi), z);
    if (std::abs(f.evaluate(q)) < 1e-12) p.push_back(q);
  }
  return p;
}

// n values from a to b, evenly spaced.
std::vector<double> spaced(double a, double b, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(a + (b - a) * i / (n - 1));
  return v;
}

Points<3> toPoints(const std::vector<std::vector<Vec<3>>>& parts) {
  std::vector<Vec<3>> all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  Points<3> P(3, static_cast<Eigen::Index>(all.size()));
  for (size_t i = 0; i < all.size(); ++i) P.col(static_cast<Eigen::Index>(i)) = all[i];
  return P;
}

// Two balls of radius 0.3 at x = ±0.5 joined by a rod of radius `rod` along kAxis, with samples
// on the rod (outside the balls) and on the balls (outside the rod).
struct Dumbbell {
  BallsAndRod field;
  Points<3> samples;
  explicit Dumbbell(double rod)
      : field({{Vec<3>(-0.5, 0, 0), 0.3}, {Vec<3>(0.5, 0, 0), 0.3}}, -0.5, 0.5, rod),
        samples(toPoints({ringSamples(field, spaced(-0.2, 0.2, 41), rod),
                          sphereSamples(field, Vec<3>(-0.5, 0, 0), 0.3, 400),
                          sphereSamples(field, Vec<3>(0.5, 0, 0), 0.3, 400)})) {}
};

std::uint64_t gFakeBytes = 0;
AvailableMemory fakeAvailable() { return {gFakeBytes, "test limit"}; }

// The 32-cell grid over kBox that the fields above are laid out for.
MarchingOptions grid32() {
  MarchingOptions o;
  o.resolution = 32;
  return o;
}

// The mesh with anchors, and its report, for a field whose refinement is left out for `why`:
// the anchors are missed, yet the mesh is the one without anchors.
std::pair<TriMesh, MarchingReport> meshLeftUnrefined(const ImplicitField<3>& field, const Points<3>& anchors,
                                                     MarchingReport::Refinement why) {
  MarchingOptions options = grid32();
  const TriMesh plain = marchingCubes(field, kBox, options);
  options.anchors = &anchors;
  MarchingReport r;
  TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.missedAnchors > 0);
  CHECK(r.refinement == why);
  CHECK(r.refinedCells[0] == 0);
  CHECK(mesh.triangles == plain.triangles);
  return {std::move(mesh), r};
}

MeshCheck check(const TriMesh& mesh, const MarchingReport& r) { return checkMesh(mesh, 1e-9 * r.minStep * r.minStep); }

}  // namespace

TEST_CASE("grid lines: uniform, cell lookup and split intervals") {
  const GridLines<3> lines = uniformGridLines<3>(kBox, {4, 2, 1});
  CHECK(gridCells<3>(lines) == std::array<int, 3>{4, 2, 1});
  CHECK(lines[0][2] == doctest::Approx(0.0));
  CHECK(gridCellOf(lines[0], -1.0) == 0);
  CHECK(gridCellOf(lines[0], 0.49) == 2);
  CHECK(gridCellOf(lines[0], 1.0) == 3);  // the last line belongs to the last cell
  CHECK(gridCellOf(lines[0], 1.01) == -1);
  const auto near = intervalsNear<3>(lines, {{1, 0, 0}}, 1);
  CHECK(near[0] == std::vector<char>{1, 1, 1, 0});
  CHECK(near[1] == std::vector<char>{1, 1});
  const GridLines<3> split = splitGridIntervals<3>(lines, near, 4);
  CHECK(gridCells<3>(split) == std::array<int, 3>{13, 8, 4});
  for (int a = 0; a < 3; ++a)
    for (size_t i = 0; i + 1 < split[a].size(); ++i) CHECK(split[a][i] < split[a][i + 1]);
  CHECK(split[0][1] == doctest::Approx(-0.875));  // the first interval [−1, −0.5] in quarters
  CHECK(split[0].back() == 1.0);
}

TEST_CASE("marching cubes: a neck thinner than a cell joins again where anchors lie on it") {
  const Dumbbell dumbbell(0.02);
  const ImplicitField<3>& field = dumbbell.field;
  MarchingOptions options = grid32();
  MarchingReport plain;
  const TriMesh uniform = marchingCubes(field, kBox, options, &plain);
  REQUIRE(connectedComponentCount(uniform) == 2);  // the grid steps over the rod
  options.anchors = &dumbbell.samples;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.missedAnchors > 0);
  CHECK(r.refinement == MarchingReport::Refinement::Refined);
  CHECK(r.cells == plain.cells);  // the report keeps the uniform grid's cells
  CHECK(r.refinedCells[0] > r.cells[0]);
  CHECK(r.refinedCells[0] <= 2 * r.cells[0]);
  CHECK(r.minStep == doctest::Approx(2.0 / 32 / kAnchorSplit));
  CHECK(connectedComponentCount(mesh) == 1);
  const MeshCheck c = check(mesh, r);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 2);
  for (Eigen::Index v = 0; v < mesh.vertices.cols(); ++v)
    REQUIRE(std::abs(field.evaluate(mesh.vertices.col(v))) < 2e-3);  // on the zero set (the union's kinks aside)
  SUBCASE("the dense grid refines alike") {
    options.cull = false;
    MarchingReport rd;
    const TriMesh dense = marchingCubes(field, kBox, options, &rd);
    CHECK(rd.refinedCells == r.refinedCells);
    CHECK(dense.triangleCount() == mesh.triangleCount());
    CHECK(connectedComponentCount(dense) == 1);
  }
}

TEST_CASE("marching cubes: a thin stub the grid steps over is refined where its samples lie off the mesh") {
  // A ball with a rod of radius 0.02 from it to x = −0.05: one piece, the stub's samples up to
  // 0.15 (1.4 cell diagonals) off it.
  const BallsAndRod field({{Vec<3>(-0.5, 0, 0), 0.3}}, -0.5, -0.05, 0.02);
  const Points<3> anchors = toPoints({ringSamples(field, spaced(-0.18, -0.05, 14), 0.02)});
  MarchingOptions options = grid32();
  const TriMesh plain = marchingCubes(field, kBox, options);
  REQUIRE(connectedComponentCount(plain) == 1);
  const std::vector<double> before = distancesToMeshWithin(plain, anchors, 1.0);
  CHECK(*std::max_element(before.begin(), before.end()) > 0.1);
  options.anchors = &anchors;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.refinement == MarchingReport::Refinement::Refined);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(check(mesh, r).closedManifold());
  // The refined grid's cells are a quarter as wide there: the stub's samples lie within one of
  // their diagonals of the mesh.
  const std::vector<double> after = distancesToMeshWithin(mesh, anchors, 1.0);
  CHECK(*std::max_element(after.begin(), after.end()) < 2.0 / 32 / kAnchorSplit * std::sqrt(3.0));
}

TEST_CASE("marching cubes: a thin stub off its samples that only halving could refine is left as it is") {
  // The stub runs on to x = 0.6: cut in kAnchorSplit its cells would more than double the x axis.
  const BallsAndRod field({{Vec<3>(-0.5, 0, 0), 0.3}}, -0.5, 0.6, 0.02);
  const Points<3> anchors = toPoints({ringSamples(field, spaced(-0.1, 0.6, 71), 0.02)});
  const auto [mesh, r] = meshLeftUnrefined(field, anchors, MarchingReport::Refinement::TooLarge);
  CHECK(connectedComponentCount(mesh) == 1);
}

TEST_CASE("marching cubes: a thin stub whose samples lie within half a cell diagonal of the mesh is not refined") {
  // The rod ends 0.03 beyond the ball (radius 0.3 about x = −0.5): its samples are missed but
  // within 0.054, half a cell diagonal, of the ball's mesh.
  const BallsAndRod field({{Vec<3>(-0.5, 0, 0), 0.3}}, -0.5, -0.17, 0.02);
  const Points<3> anchors = toPoints({ringSamples(field, spaced(-0.195, -0.17, 6), 0.02)});
  const auto [mesh, r] = meshLeftUnrefined(field, anchors, MarchingReport::Refinement::OnePiece);
  CHECK(connectedComponentCount(mesh) == 1);
}

TEST_CASE("marching cubes: a refined pass that shows more pieces is dropped") {
  // A ball, beads of radius 0.012 every 0.05 along kAxis from x = −0.1 to 0.6 (pieces of their
  // own, which a finer grid shows) and a ball of radius 0.1 at (0.75, 0, 0) that the grid sees.
  std::vector<Ball> balls{{Vec<3>(-0.5, 0, 0), 0.3}, {Vec<3>(0.75, 0, 0), 0.1}};
  const std::vector<double> beads = spaced(-0.1, 0.6, 15);
  for (double x : beads) balls.push_back({Vec<3>(x, kAxis, kAxis), 0.012});
  const BallsAndRod field(balls);
  const Points<3> anchors = toPoints({ringSamples(field, beads, 0.012)});
  const auto [mesh, r] = meshLeftUnrefined(field, anchors, MarchingReport::Refinement::NoGain);
  CHECK(connectedComponentCount(mesh) == 2);  // the two balls; the grid catches no bead
  CHECK(r.evaluatedPoints > 0);
}

TEST_CASE("marching cubes: anchors on a surface the grid resolves change nothing") {
  const Dumbbell dumbbell(0.09);  // a rod thicker than a cell
  const ImplicitField<3>& field = dumbbell.field;
  MarchingOptions options = grid32();
  const TriMesh plain = marchingCubes(field, kBox, options);
  options.anchors = &dumbbell.samples;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.missedAnchors == 0);
  CHECK(r.refinement == MarchingReport::Refinement::None);
  REQUIRE(mesh.vertexCount() == plain.vertexCount());
  CHECK(mesh.vertices == plain.vertices);
  CHECK(mesh.triangles == plain.triangles);
}

TEST_CASE("marching cubes: a refinement beyond half the available memory is left out and reported") {
  const Dumbbell dumbbell(0.02);
  const ImplicitField<3>& field = dumbbell.field;
  MarchingOptions options = grid32();
  options.anchors = &dumbbell.samples;
  gFakeBytes = 300 * 1024;  // the uniform slabs (33 × 33 × 33 points) are below the checked size
  setAvailableMemorySource(fakeAvailable);
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  setAvailableMemorySource(nullptr);
  CHECK(r.missedAnchors > 0);
  CHECK(r.refinement == MarchingReport::Refinement::TooLarge);
  CHECK(r.refinedCells[0] == 0);
  CHECK(connectedComponentCount(mesh) == 2);
}
