// The data reach of a partition-of-unity field (pu_data_reach.h; docs/maths.md, "No data"):
// points sampled from a closed mesh with thin parts reconstruct as one watertight component near
// the true surface at the sampling's grid step and at a finer one, and the reach follows the
// sampling density.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "core/pu/pu_model.h"
#include "support/mesh_distance.h"
#include "support/mesh_samples.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// Signed distance to a capsule: the segment a–b thickened by r.
double capsule(const Vec<3>& x, const Vec<3>& a, const Vec<3>& b, double r) {
  const Vec<3> ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm() - r;
}

// An armadillo-like solid: an ellipsoidal body with thin limbs, two thin "fingers" 2.5 sample
// spacings apart, and an ear; f = the smallest of the parts' signed distances (exact outside).
class CreatureField final : public ImplicitField<3> {
 public:
  // The signed distance (exact outside).
  double sdf(const Vec<3>& x) const {
    const double body = (x.cwiseQuotient(Vec<3>(0.6, 0.45, 0.4)).norm() - 1.0) * 0.4;
    double f = body;
    f = std::min(f, capsule(x, Vec<3>(0.3, 0.2, 0), Vec<3>(0.9, 0.6, 0.1), 0.07));
    f = std::min(f, capsule(x, Vec<3>(-0.3, 0.2, 0), Vec<3>(-0.9, 0.6, 0.1), 0.07));
    f = std::min(f, capsule(x, Vec<3>(0.2, -0.3, 0), Vec<3>(0.3, -0.95, 0.0), 0.06));
    f = std::min(f, capsule(x, Vec<3>(0.2, -0.3, 0.12), Vec<3>(0.3, -0.95, 0.12), 0.035));  // finger beside the leg
    f = std::min(f, capsule(x, Vec<3>(-0.1, 0.0, 0.3), Vec<3>(-0.2, 0.1, 0.75), 0.05));      // ear
    return f;
  }
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    if (g || H) {  // central differences suffice for the meshing's vertex refinement
      const double e = 1e-6;
      Vec<3> d;
      for (int k = 0; k < 3; ++k) {
        Vec<3> p = x, m = x;
        p(k) += e;
        m(k) -= e;
        d(k) = (sdf(p) - sdf(m)) / (2 * e);
      }
      if (g) *g = d;
      if (H) H->setZero();
    }
    return sdf(x);
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }
};

Box<3> grownBox(const Points<3>& P, double margin) {
  Box<3> b{P.rowwise().minCoeff(), P.rowwise().maxCoeff()};
  const double d = margin * b.extent().norm();
  b.lo.array() -= d;
  b.hi.array() += d;
  return b;
}

}  // namespace

TEST_CASE("pu data reach: 20 000 samples of a closed mesh with thin parts: one watertight component near the surface") {
  const CreatureField truth;
  MarchingOptions fine;
  fine.resolution = 160;
  fine.cull = false;
  const TriMesh truthMesh = marchingCubes(truth, Box<3>{Vec<3>(-1.1, -1.1, -0.6), Vec<3>(1.1, 1.0, 0.9)}, fine);
  REQUIRE(checkMesh(truthMesh).closedManifold());
  const HermiteSamples<3> s = testing::sampleMesh(truthMesh, 20000, 17);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  const PuModel<3> pu = fitPu<3>(s, o);
  const Box<3> bounds = grownBox(s.points, 0.25);  // view bounds well beyond the data
  const double diagonal = (s.points.rowwise().maxCoeff() - s.points.rowwise().minCoeff()).norm();
  // At about the sampling's spacing and at half of it: closed either way.
  for (int resolution : {96, 192}) {
    CAPTURE(resolution);
    MarchingOptions mo;
    mo.resolution = resolution;
    const TriMesh mesh = marchingCubes(pu, bounds, mo);
    const MeshCheck check = checkMesh(mesh);
    CHECK(check.components == 1);
    CHECK(check.closedManifold());
    CHECK(check.eulerCharacteristic == 2);  // a sphere's topology: limbs and ear attached, none fused
    double worst = 0;
    for (int v = 0; v < mesh.vertexCount(); ++v) worst = std::max(worst, std::abs(truth.sdf(mesh.vertices.col(v))));
    MESSAGE("creature at " << resolution << ": " << mesh.triangleCount() << " triangles, farthest vertex "
                           << 100 * worst / diagonal << " % of the diagonal");
    CHECK(worst <= 0.005 * diagonal);
  }
}

TEST_CASE("pu data reach: the reach follows the local spacing up to twice the median, and no data far from every sample") {
  // A dense patch and a sparse one (4 times the spacing) of the same plane: the reach scales with
  // the dense one's spacing, and the sparse one's is capped at twice the median spacing.
  HermiteSamples<3> s;
  const int dense = 60, sparse = 15;
  s.points.resize(3, dense * dense + sparse * sparse);
  s.normals.resize(3, s.points.cols());
  int c = 0;
  for (int i = 0; i < dense; ++i)
    for (int j = 0; j < dense; ++j) s.points.col(c++) = Vec<3>(i / double(dense), j / double(dense), 0);
  for (int i = 0; i < sparse; ++i)
    for (int j = 0; j < sparse; ++j) s.points.col(c++) = Vec<3>(2 + i / double(sparse), j / double(sparse), 0);
  s.normals.colwise() = Vec<3>(0, 0, 1);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.dataReach = 3.0;
  const PuModel<3> pu = fitPu<3>(s, o);
  // k = 6 neighbours on a square grid of step a: d₆ = √2·a, so the reach is 3√2·a ≈ 4.24 a.
  const double aDense = 1.0 / dense, aSparse = 1.0 / sparse;
  const auto reaches = [&](const PuModel<3>& m, const Vec<3>& y) { return m.dataReach().reaches(m.tree(), y); };
  CHECK(reaches(pu, Vec<3>(0.5, 0.5, 4.2 * aDense)));
  CHECK_FALSE(reaches(pu, Vec<3>(0.5, 0.5, 4.3 * aDense)));
  // The sparse patch: 3·min(√2·aSparse, 2·√2·aDense) = 8.49 aDense (uncapped: 16.97).
  const Vec<3> sparseCentre(2 + 7 * aSparse, 7 * aSparse, 0);
  CHECK(reaches(pu, sparseCentre + Vec<3>(0, 0, 8.4 * aDense)));
  CHECK_FALSE(reaches(pu, sparseCentre + Vec<3>(0, 0, 8.6 * aDense)));
  CHECK(pu.valid(Vec<3>(0.5, 0.5, 0.0)));
  CHECK_FALSE(pu.valid(Vec<3>(1.5, 0.5, 0.0)));  // between the patches, far from both
  PuOptions wide = o;
  wide.dataReach = 6.0;
  CHECK(reaches(fitPu<3>(s, wide), Vec<3>(0.5, 0.5, 8.4 * aDense)));
}

TEST_CASE("pu data reach: a sparse row of samples reaches at most twice the median spacing (oni.pwn's neck)") {
  // A dense patch (step a) and, apart from it, one row of 11 samples 0.1 apart: a row sample's
  // 6th neighbour is 3 steps away, so uncapped its reach would be 3·0.3 = 0.9, most of the data.
  HermiteSamples<3> s;
  const int side = 60, row = 11;
  s.points.resize(3, side * side + row);
  s.normals.resize(3, s.points.cols());
  int c = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) s.points.col(c++) = Vec<3>(i / double(side), j / double(side), 0);
  for (int i = 0; i < row; ++i) s.points.col(c++) = Vec<3>(0.1 * i, 2.0, 0);
  s.normals.colwise() = Vec<3>(0, 0, 1);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  const PuModel<3> pu = fitPu<3>(s, o);
  const double cap = 2 * 3 * std::sqrt(2.0) / side;  // 2 × c × the median d₆ (the dense patch's)
  const Vec<3> middle(0.5, 2.0, 0);                  // the row's 6th sample
  const auto reaches = [&](const Vec<3>& y) { return pu.dataReach().reaches(pu.tree(), y); };
  CHECK(reaches(middle + Vec<3>(0, 0, 0.98 * cap)));
  CHECK_FALSE(reaches(middle + Vec<3>(0, 0, 1.02 * cap)));
  CHECK(pu.dataReach().maxRadius() <= cap * (1 + 1e-12));
}

TEST_CASE("pu data reach: with the edge test an open surface ends about half a reach past its last samples") {
  // A hemisphere (z ≥ 0) of 4 000 samples. With the zero-set reach as wide as the data reach
  // (vertexReach = dataReach): without the edge test the zero set runs on below the rim until the
  // reach nearly ends (0.8 of the largest reach); with it (z = 5) within half of one. With the
  // default zero-set reach (2 spacings, no edge test) within 2/3 of one.
  const HermiteSamples<3> sphere = testing::goldenSphere(8000);
  std::vector<int> keep;
  for (int i = 0; i < sphere.size(); ++i)
    if (sphere.points(2, i) >= 0) keep.push_back(i);
  HermiteSamples<3> s;
  s.points = sphere.points(Eigen::all, keep);
  s.normals = sphere.normals(Eigen::all, keep);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.edgeShift = 5;
  o.vertexReach = o.dataReach;
  MarchingOptions mo;
  mo.resolution = 96;
  const Box<3> bounds = grownBox(s.points, 0.25);
  const auto farthest = [&](const PuModel<3>& pu, const TriMesh& mesh) {
    double worst = 0;
    for (int v = 0; v < mesh.vertexCount(); ++v)
      worst = std::max(worst, (s.points.colwise() - mesh.vertices.col(v)).colwise().norm().minCoeff());
    return worst / pu.dataReach().maxRadius();
  };
  const PuModel<3> pu = fitPu<3>(s, o);
  const TriMesh mesh = marchingCubes(pu, bounds, mo);
  const MeshCheck check = checkMesh(mesh);
  CHECK(check.components == 1);
  CHECK(check.boundaryEdges > 0);  // open at the rim
  PuOptions noTest = o;
  noTest.edgeShift = 0;  // the default
  const PuModel<3> plain = fitPu<3>(s, noTest);
  const double with = farthest(pu, mesh), without = farthest(plain, marchingCubes(plain, bounds, mo));
  MESSAGE("hemisphere: farthest vertex from the data " << with << " reaches with the edge test, " << without
                                                       << " without");
  CHECK(with <= 0.55);
  CHECK(without >= 0.7);  // the test is what ends it
  PuOptions defaults = o;
  defaults.edgeShift = 0;
  defaults.vertexReach = PuOptions{}.vertexReach;
  const PuModel<3> narrow = fitPu<3>(s, defaults);
  const double zeroSetReach = farthest(narrow, marchingCubes(narrow, bounds, mo));
  // Edge vertices within (β/c)·rᵢ; a centre vertex (a polygon's mean) within a cell diagonal more.
  const double cellDiagonal = std::sqrt(3.0) * bounds.extent().maxCoeff() / mo.resolution;
  MESSAGE("default zero-set reach: " << zeroSetReach << " reaches");
  CHECK(zeroSetReach <= defaults.vertexReach / defaults.dataReach + cellDiagonal / narrow.dataReach().maxRadius());
}

TEST_CASE("pu data reach: a box with sharp edges and corners gives one watertight component") {
  // 20 000 samples of the faces of a 2 × 1.5 × 1 box with their exact normals: the edge test
  // must not take its edges (0.7 σ) or corners (1.6 σ) for the edge of the data.
  TriMesh box;
  box.vertices.resize(3, 8);
  for (int i = 0; i < 8; ++i) box.vertices.col(i) = Vec<3>(i & 1 ? 1.0 : -1.0, i & 2 ? 0.75 : -0.75, i & 4 ? 0.5 : -0.5);
  box.triangles.resize(3, 12);
  box.triangles << 0, 0, 4, 4, 0, 0, 2, 2, 0, 0, 1, 1,  //
      2, 3, 5, 7, 1, 5, 6, 7, 4, 6, 3, 7,                //
      3, 1, 7, 6, 5, 4, 7, 3, 6, 2, 7, 5;
  REQUIRE(checkMesh(box).closedManifold());
  REQUIRE(signedVolume(box) > 0);  // outward
  const HermiteSamples<3> s = testing::sampleMesh(box, 20000, 17);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.edgeShift = 5;  // the edge test on: edges and corners must pass it
  const PuModel<3> pu = fitPu<3>(s, o);
  MarchingOptions mo;
  mo.resolution = 96;
  const TriMesh mesh = marchingCubes(pu, grownBox(s.points, 0.25), mo);
  const MeshCheck check = checkMesh(mesh);
  CHECK(check.components == 1);
  CHECK(check.closedManifold());
  CHECK(check.eulerCharacteristic == 2);
  double worst = 0;  // distance to the box surface
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vec<3> d = mesh.vertices.col(v).cwiseAbs() - Vec<3>(1.0, 0.75, 0.5);
    const double outside = d.cwiseMax(0.0).norm(), inside = std::min(d.maxCoeff(), 0.0);
    worst = std::max(worst, std::abs(outside + inside));
  }
  const double diagonal = Vec<3>(2, 1.5, 1).norm();
  MESSAGE("box: " << mesh.triangleCount() << " triangles, farthest vertex " << 100 * worst / diagonal
                  << " % of the diagonal");
  CHECK(worst <= 0.01 * diagonal);  // the rounding of the edges at a 96³ grid
}

namespace {

// The field of a PU model whose mesher margin is switched off (validNear = valid): the rule
// before the widening, to show that a test's grid is coarse enough to need it.
class WithoutMargin final : public ImplicitField<3> {
 public:
  explicit WithoutMargin(const PuModel<3>& pu) : pu_(pu) {}
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override { return pu_.evaluate(x, g, H); }
  void evaluateBatch(const Points<3>& X, Eigen::VectorXd& f, Points<3>* G) const override {
    pu_.evaluateBatch(X, f, G);
  }
  bool valid(const Vec<3>& x) const override { return pu_.valid(x); }
  bool validNear(const Vec<3>& x, double) const override { return pu_.valid(x); }
  bool validOnZeroSet(const Vec<3>& x) const override { return pu_.validOnZeroSet(x); }
  bool everywhereValid() const override { return false; }
  double lipschitzBound(const Box<3>& b) const override { return pu_.lipschitzBound(b); }

 private:
  const PuModel<3>& pu_;
};

}  // namespace

TEST_CASE("pu data reach: a dense sample whose reach is thinner than a grid cell still meshes closed") {
  // 10 000 samples of the unit sphere at 24³ over [-1.3, 1.3]³: the median reach rᵢ is below a
  // cell diagonal, so corners of cells the sphere crosses lie beyond every reach (the 1 000 000
  // armadillo samples at 256³ in small). The mesher widens each reach to dₖ + δ (δ the cell
  // diagonal): closed, one component, on the sphere.
  const HermiteSamples<3> s = testing::goldenSphere(10000);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  const PuModel<3> pu = fitPu<3>(s, o);
  MarchingOptions mo;
  mo.resolution = 24;
  const Box<3> bounds{Vec<3>::Constant(-1.3), Vec<3>::Constant(1.3)};
  const double cellDiagonal = std::sqrt(3.0) * 2.6 / mo.resolution;
  std::vector<double> radii(static_cast<std::size_t>(s.size()));
  for (int j = 0; j < s.size(); ++j) radii[static_cast<std::size_t>(j)] = pu.dataReach().radiusAt(j);
  std::nth_element(radii.begin(), radii.begin() + s.size() / 2, radii.end());
  const double medianReach = radii[static_cast<std::size_t>(s.size() / 2)];
  MESSAGE("median reach " << medianReach << ", cell diagonal " << cellDiagonal);
  REQUIRE(medianReach < cellDiagonal);
  const TriMesh without = marchingCubes(WithoutMargin(pu), bounds, mo);
  CHECK(checkMesh(without).boundaryEdges > 0);  // the reach alone leaves holes at this grid
  const TriMesh mesh = marchingCubes(pu, bounds, mo);
  const MeshCheck check = checkMesh(mesh);
  CHECK(check.components == 1);
  CHECK(check.closedManifold());
  CHECK(check.eulerCharacteristic == 2);
  double worst = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) worst = std::max(worst, std::abs(mesh.vertices.col(v).norm() - 1.0));
  CHECK(worst < 5e-3);  // edge vertices on the zero set, centre vertices within a flat polygon
}

TEST_CASE("pu data reach: a wedge with a sharp 45 degree edge gives one closed component near its surface") {
  // A prism over the triangle (−1, 0), (1, 0), (−1, 2), z in [−0.5, 0.5]: two 45° and four
  // right-angled sharp edges. Near a sharp edge one face's local fit continues past the edge;
  // where it dips below zero a few spacings off the other face (fandisk at 200 000 samples), the
  // zero-set reach (PuOptions::vertexReach) keeps that pocket out of the mesh. (At 30° the part of
  // the wedge thinner than a 96³ cell breaks into separate fragments on the surface, before and
  // after the zero-set reach: the grid's limit, not a sheet.)
  TriMesh wedge;
  const double top = 2.0;  // 2·tan 45°
  wedge.vertices.resize(3, 6);
  const double xy[3][2] = {{-1, 0}, {1, 0}, {-1, top}};
  for (int i = 0; i < 6; ++i) wedge.vertices.col(i) = Vec<3>(xy[i % 3][0], xy[i % 3][1], i < 3 ? -0.5 : 0.5);
  wedge.triangles.resize(3, 8);
  wedge.triangles << 0, 3, 0, 0, 1, 1, 2, 2,  //
      2, 4, 1, 4, 2, 5, 0, 3,                 //
      1, 5, 4, 3, 5, 4, 3, 5;
  if (signedVolume(wedge) < 0) wedge.triangles.row(1).swap(wedge.triangles.row(2));
  REQUIRE(checkMesh(wedge).closedManifold());
  REQUIRE(signedVolume(wedge) > 0);
  const HermiteSamples<3> s = testing::sampleMesh(wedge, 15000, 17);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  const PuModel<3> pu = fitPu<3>(s, o);
  MarchingOptions mo;
  mo.resolution = 96;
  const TriMesh mesh = marchingCubes(pu, grownBox(s.points, 0.1), mo);
  const MeshCheck check = checkMesh(mesh);
  CHECK(check.components == 1);
  CHECK(check.closedManifold());
  CHECK(check.eulerCharacteristic == 2);
  const double worst = testing::farthestFromMesh(wedge, mesh.vertices);
  const double diagonal = Vec<3>(2, top, 1).norm();
  MESSAGE("wedge: " << mesh.triangleCount() << " triangles, farthest vertex " << 100 * worst / diagonal
                    << " % of the diagonal");
  CHECK(worst <= 0.01 * diagonal);  // the rounding of the acute edge at a 96³ grid
}
