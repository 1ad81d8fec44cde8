// Marching cubes refined at anchors (MarchingOptions::anchors, marching_anchors.h): a neck
// thinner than a cell that the uniform grid steps over splits the mesh; with samples on the
// neck as anchors the grid is cut finer there and the mesh is one closed piece again. Fields
// without thin parts mesh exactly as without anchors, and a refinement that would not fit in
// memory is refused with its reason.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/base/memory_check.h"
#include "core/mesh/grid_lines.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"

using namespace hermite;

namespace {

// Two balls of radius 0.3 at x = ±0.5 joined by a rod of radius `rod` along x at y = z = 0.031:
// the signed distance to their union (1-Lipschitz). On the 32-cell grid over [−1, 1]³ (lines at
// multiples of 0.0625) the rod's axis lies 0.044 from every grid line along x, so a rod of
// radius 0.02 holds no grid point.
class Dumbbell : public ImplicitField<3> {
 public:
  explicit Dumbbell(double rod) : rod_(rod) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const Vec<3> c[2] = {Vec<3>(-0.5, 0, 0), Vec<3>(0.5, 0, 0)};
    double best = 1e300;
    Vec<3> dir = Vec<3>::UnitX();
    for (const Vec<3>& ci : c) {
      const double d = (x - ci).norm() - 0.3;
      if (d < best) best = d, dir = (x - ci).normalized();
    }
    const Vec<3> axis(std::clamp(x.x(), -0.5, 0.5), kAxis, kAxis);
    const double d = (x - axis).norm() - rod_;
    if (d < best) best = d, dir = (x - axis).normalized();
    if (g) *g = dir;
    if (H) H->setZero();
    return best;
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

  // Points on the rod's surface (outside the balls) and on the balls (outside the rod).
  Points<3> samples() const {
    std::vector<Vec<3>> p;
    for (int i = 0; i <= 40; ++i)
      for (int k = 0; k < 8; ++k) {
        const double t = 2 * M_PI * k / 8;
        const Vec<3> q(-0.2 + 0.4 * i / 40, kAxis + rod_ * std::cos(t), kAxis + rod_ * std::sin(t));
        if (std::abs(evaluate(q)) < 1e-12) p.push_back(q);
      }
    for (int i = 0; i < 400; ++i) {  // a Fibonacci sphere on each ball
      const double z = 1 - (2.0 * i + 1) / 400, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
      for (double cx : {-0.5, 0.5}) {
        const Vec<3> q = Vec<3>(cx, 0, 0) + 0.3 * Vec<3>(r * std::cos(phi), r * std::sin(phi), z);
        if (std::abs(evaluate(q)) < 1e-12) p.push_back(q);
      }
    }
    Points<3> P(3, static_cast<Eigen::Index>(p.size()));
    for (size_t i = 0; i < p.size(); ++i) P.col(static_cast<Eigen::Index>(i)) = p[i];
    return P;
  }

 private:
  static constexpr double kAxis = 0.031;
  double rod_;
};

const Box<3> kBox{Vec<3>::Constant(-1.0), Vec<3>::Constant(1.0)};

// A ball of radius 0.3 at (−0.5, 0, 0) and, along x at y = z = 0.031 (off every grid line, as
// the dumbbell's rod), either a rod of radius 0.02 from the ball to x = 0.6 (one piece with a
// stub the grid steps over) or beads of radius 0.012 every 0.05 from x = −0.1 to 0.6 (pieces of
// their own that a finer grid shows) and a ball of radius 0.1 at (0.75, 0, 0): the signed
// distance to the union.
class BallWith : public ImplicitField<3> {
 public:
  explicit BallWith(bool beads) : beads_(beads) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const Vec<3> c(-0.5, 0, 0);
    double best = (x - c).norm() - 0.3;
    Vec<3> dir = (x - c).normalized();
    const auto take = [&](const Vec<3>& p, double r) {
      const double d = (x - p).norm() - r;
      if (d < best) best = d, dir = (x - p).normalized();
    };
    if (beads_) {
      for (int i = 0; i <= 14; ++i) take(Vec<3>(-0.1 + 0.05 * i, 0.031, 0.031), 0.012);
      take(Vec<3>(0.75, 0, 0), 0.1);  // a ball the grid sees
    }
    else
      take(Vec<3>(std::clamp(x.x(), -0.5, 0.6), 0.031, 0.031), 0.02);
    if (g) *g = dir;
    if (H) H->setZero();
    return best;
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }
  // Points on the rod or the beads (their equators around x) that lie on the zero set.
  Points<3> samples() const {
    std::vector<Vec<3>> p;
    const double r = beads_ ? 0.012 : 0.02;
    for (int i = 0; i <= 70; ++i)
      for (int k = 0; k < 8; ++k) {
        const double t = 2 * M_PI * k / 8, x = beads_ ? -0.1 + 0.05 * (i / 5) : -0.1 + 0.7 * i / 70;
        const Vec<3> q(x, 0.031 + r * std::cos(t), 0.031 + r * std::sin(t));
        if (std::abs(evaluate(q)) < 1e-12) p.push_back(q);
      }
    Points<3> P(3, static_cast<Eigen::Index>(p.size()));
    for (size_t i = 0; i < p.size(); ++i) P.col(static_cast<Eigen::Index>(i)) = p[i];
    return P;
  }

 private:
  bool beads_;
};

std::uint64_t gFakeBytes = 0;
AvailableMemory fakeAvailable() { return {gFakeBytes, "test limit"}; }

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
  const Dumbbell field(0.02);
  const Points<3> anchors = field.samples();
  MarchingOptions options;
  options.resolution = 32;
  MarchingReport plain;
  const TriMesh uniform = marchingCubes(field, kBox, options, &plain);
  REQUIRE(connectedComponentCount(uniform) == 2);  // the grid steps over the rod
  options.anchors = &anchors;
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

TEST_CASE("marching cubes: a thin stub that leaves the mesh in one piece is not refined") {
  const BallWith field(false);
  const Points<3> anchors = field.samples();
  MarchingOptions options;
  options.resolution = 32;
  const TriMesh plain = marchingCubes(field, kBox, options);
  options.anchors = &anchors;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.missedAnchors > 0);
  CHECK(r.refinement == MarchingReport::Refinement::OnePiece);
  CHECK(r.refinedCells[0] == 0);
  CHECK(connectedComponentCount(mesh) == 1);
  CHECK(mesh.triangles == plain.triangles);
}

TEST_CASE("marching cubes: a refined pass that shows more pieces is dropped") {
  const BallWith field(true);
  const Points<3> anchors = field.samples();
  MarchingOptions options;
  options.resolution = 32;
  const TriMesh plain = marchingCubes(field, kBox, options);
  REQUIRE(connectedComponentCount(plain) == 2);  // the two balls; the grid catches no bead
  options.anchors = &anchors;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.missedAnchors > 0);
  CHECK(r.refinement == MarchingReport::Refinement::NoGain);
  CHECK(r.refinedCells[0] == 0);
  CHECK(r.evaluatedPoints > 0);
  CHECK(mesh.triangles == plain.triangles);
}

TEST_CASE("marching cubes: anchors on a surface the grid resolves change nothing") {
  const Dumbbell field(0.09);  // a rod thicker than a cell
  const Points<3> anchors = field.samples();
  MarchingOptions options;
  options.resolution = 32;
  const TriMesh plain = marchingCubes(field, kBox, options);
  options.anchors = &anchors;
  MarchingReport r;
  const TriMesh mesh = marchingCubes(field, kBox, options, &r);
  CHECK(r.missedAnchors == 0);
  CHECK(r.refinement == MarchingReport::Refinement::None);
  REQUIRE(mesh.vertexCount() == plain.vertexCount());
  CHECK(mesh.vertices == plain.vertices);
  CHECK(mesh.triangles == plain.triangles);
}

TEST_CASE("marching cubes: a refinement beyond half the available memory is left out and reported") {
  const Dumbbell field(0.02);
  const Points<3> anchors = field.samples();
  MarchingOptions options;
  options.resolution = 32;
  options.anchors = &anchors;
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
