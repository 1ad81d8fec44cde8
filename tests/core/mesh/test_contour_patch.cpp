// Contouring part of a grid again (contour_patch.h): the patched contour is the whole grid's
// contour of the changed field, triangle for triangle, on uniform and on refined lines; blocks
// about nearby centres merge; a field that changed on a block's faces is refused.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "core/mesh/contour_patch.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "support/triangle_set.h"

using namespace hermite;
using hermite::testing::triangleSet;

namespace {

const Vec<3> kBumpCentre(1, 0, 0);
constexpr double kBumpRadius = 0.3;

// The unit sphere's signed distance, plus an outward bump of height `bump` within kBumpRadius of
// kBumpCentre, plus a constant `shift` everywhere; with a blob, the union with a ball of that
// radius at kBlobCentre.
const Vec<3> kBlobCentre(1.3, 0.3, 0);

class BumpySphere final : public ImplicitField<3> {
 public:
  double bump = 0, shift = 0, blob = 0;
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    double f = x.norm() - 1 + shift;
    Vec<3> grad = x.normalized();
    if (blob > 0 && (x - kBlobCentre).norm() - blob < f) {
      f = (x - kBlobCentre).norm() - blob;
      grad = (x - kBlobCentre).normalized();
    }
    const Vec<3> d = x - kBumpCentre;
    const double s = d.squaredNorm() / (kBumpRadius * kBumpRadius);
    if (s < 1) {
      f -= bump * (1 - s);
      grad += bump * 2 * d / (kBumpRadius * kBumpRadius);
    }
    if (g) *g = grad;
    if (H) H->setZero();
    return f;
  }
  double lipschitzBound(const Box<3>&) const override { return 1 + 2 * bump / kBumpRadius; }
};

const Box<3> kBox{Vec<3>::Constant(-1.5), Vec<3>::Constant(1.5)};

}  // namespace

TEST_CASE("contour patch: the patched contour is the whole grid's, on uniform and refined lines") {
  MarchingOptions options;
  options.resolution = 40;
  const Vec<3> h = Vec<3>::Constant(3.0 / 40);
  GridLines<3> uniform;
  const BumpySphere sphere;
  BumpySphere bumpy;
  bumpy.bump = 0.12;
  const TriMesh before = marchingCubes(sphere, kBox, options, nullptr, &uniform);
  REQUIRE(uniform[0].size() == 41);
  // Refined lines: every interval within two cells of the bump's centre cut in four.
  std::array<std::vector<char>, 3> near;
  for (int a = 0; a < 3; ++a) {
    near[a].assign(40, 0);
    const int c = gridCellOf(uniform[a], kBumpCentre[a]);
    for (int i = c - 2; i <= c + 2; ++i) near[a][static_cast<size_t>(i)] = 1;
  }
  const GridLines<3> refined = splitGridIntervals<3>(uniform, near, 4);
  for (const GridLines<3>& lines : {uniform, refined}) {
    const TriMesh old = marchingCubesPass(sphere, lines, h, options);
    const std::vector<CellBlock> blocks = cellBlocksAround(lines, {kBumpCentre}, kBumpRadius);
    REQUIRE(blocks.size() == 1);
    const std::optional<TriMesh> patched = patchContour(old, bumpy, lines, h, blocks, options);
    REQUIRE(patched.has_value());
    CHECK(checkMesh(*patched).closedManifold());
    CHECK(triangleSet(*patched) == triangleSet(marchingCubesPass(bumpy, lines, h, options)));
    CHECK(triangleSet(*patched) != triangleSet(old));  // the bump is there
  }
  CHECK(triangleSet(marchingCubesPass(sphere, uniform, h, options)) == triangleSet(before));
}

TEST_CASE("contour patch: a field that changed on a block's faces is refused") {
  MarchingOptions options;
  options.resolution = 24;
  GridLines<3> lines;
  const BumpySphere sphere;
  const TriMesh old = marchingCubes(sphere, kBox, options, nullptr, &lines);
  BumpySphere shifted;
  shifted.shift = -0.05;  // a larger sphere: the faces' vertices move to other edges or along them
  const std::vector<CellBlock> blocks = cellBlocksAround(lines, {kBumpCentre}, kBumpRadius);
  const Vec<3> h = Vec<3>::Constant(3.0 / 24);
  CHECK_FALSE(patchContour(old, shifted, lines, h, blocks, options).has_value());
}

TEST_CASE("contour patch: a piece the review left out that reaches into a block must be left out again") {
  // A sphere and a small ball beside it; the review keeps the largest piece only. A block about
  // the bump's centre cuts through the ball, so its pass makes the ball's part inside, whose
  // vertices on the block's faces have no old twin.
  BumpySphere field;
  field.blob = 0.15;
  MarchingOptions options;
  options.resolution = 40;
  int reviews = 0;
  options.review = [&](TriMesh& mesh, const GridLines<3>&) {
    ++reviews;
    int pieces = 0;
    const std::vector<int> piece = vertexConnectedComponents(mesh, &pieces);
    std::vector<int> size(static_cast<size_t>(pieces), 0);
    for (int c : piece) ++size[static_cast<size_t>(c)];
    std::vector<char> small(static_cast<size_t>(pieces), 0);
    for (int c = 0; c < pieces; ++c) small[static_cast<size_t>(c)] = size[static_cast<size_t>(c)] * 10 < mesh.triangleCount();
    dropComponents(mesh, piece, small);
  };
  GridLines<3> lines;
  const TriMesh old = marchingCubes(field, kBox, options, nullptr, &lines);
  REQUIRE(connectedComponentCount(old) == 1);
  const Vec<3> h = Vec<3>::Constant(3.0 / 40);
  const std::vector<CellBlock> blocks = cellBlocksAround(lines, {kBumpCentre}, kBumpRadius);
  reviews = 0;
  const std::optional<TriMesh> patched = patchContour(old, field, lines, h, blocks, options);
  CHECK(reviews == 1);
  REQUIRE(patched.has_value());
  CHECK(triangleSet(*patched) == triangleSet(old));  // the same field: the same contour
  MarchingOptions unreviewed = options;
  unreviewed.review = {};
  CHECK_FALSE(patchContour(old, field, lines, h, blocks, unreviewed).has_value());
}

TEST_CASE("contour patch: blocks about nearby centres merge, far ones stay apart, all within the grid") {
  GridLines<3> lines = uniformGridLines<3>(kBox, {30, 30, 30});  // cells of 0.1
  const std::vector<CellBlock> one = cellBlocksAround(lines, {Vec<3>(0, 0, 0), Vec<3>(0.15, 0, 0)}, 0.2);
  REQUIRE(one.size() == 1);
  const std::vector<CellBlock> two = cellBlocksAround(lines, {Vec<3>(-1, 0, 0), Vec<3>(1, 0, 0), Vec<3>(1, 0.05, 0)}, 0.2);
  REQUIRE(two.size() == 2);
  for (int a = 0; a < 3; ++a) CHECK((two[0].lo[a] > two[1].hi[a] || two[1].lo[a] > two[0].hi[a]) == (a == 0));
  // A centre at the box's corner: the block is clamped to the grid.
  const std::vector<CellBlock> corner = cellBlocksAround(lines, {Vec<3>::Constant(1.5)}, 0.25);
  REQUIRE(corner.size() == 1);
  for (int a = 0; a < 3; ++a) {
    CHECK(corner[0].hi[a] == 30);
    CHECK(corner[0].lo[a] == 27 - 1);  // 1.5 − 0.25 lies in cell 27 (from 1.2 to 1.3); one more
  }
  // Blocks merged transitively: a chain of centres 0.5 apart, each block touching the next.
  const std::vector<CellBlock> chain =
      cellBlocksAround(lines, {Vec<3>(-1, 0, 0), Vec<3>(0, 0, 0), Vec<3>(-0.5, 0, 0), Vec<3>(0.5, 0, 0)}, 0.2);
  CHECK(chain.size() == 1);
}
