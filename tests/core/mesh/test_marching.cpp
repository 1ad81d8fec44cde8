#include <doctest/doctest.h>

#include <cmath>

#include "core/base/errors.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/marching_squares.h"
#include "core/mesh/tri_mesh.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/presets.h"

using namespace hermite;

namespace {

// f = sin x cos y + sin y cos z + sin z cos x − 0.1 (a gyroid): many ambiguous faces at coarse
// resolution, and a zero set that leaves the box.
class GyroidField final : public ImplicitField<3> {
 public:
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    const double sx = std::sin(x[0]), cx = std::cos(x[0]), sy = std::sin(x[1]), cy = std::cos(x[1]),
                 sz = std::sin(x[2]), cz = std::cos(x[2]);
    if (g) *g = Vec<3>(cx * cy - sz * sx, -sx * sy + cy * cz, -sy * sz + cz * cx);
    if (H) H->setZero();  // unused here
    return sx * cy + sy * cz + sz * cx - 0.1;
  }
  double lipschitzBound(const Box<3>&) const override { return 2 * std::sqrt(3.0); }  // each component ≤ 2
};

// Two circles of radius 0.5 whose centres are 1.02 apart: at coarse resolution the cells between
// them are ambiguous.
class TwoCircles final : public ImplicitField<2> {
 public:
  double evaluate(const Vec<2>& x, Vec<2>* g, Mat<2>* H) const override {
    const Vec<2> a(-0.51, 0), b(0.51, 0);
    const double da = (x - a).norm(), db = (x - b).norm();
    const bool nearA = da < db;
    const Vec<2> d = nearA ? Vec<2>(x - a) : Vec<2>(x - b);
    if (g) *g = d / std::max(d.norm(), 1e-300);
    if (H) H->setZero();
    return std::min(da, db) - 0.5;
  }
  double lipschitzBound(const Box<2>&) const override { return 1.0; }
};

Box<3> cube(double half) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-half);
  b.hi = Vec<3>::Constant(half);
  return b;
}

double signedArea(const Points<2>& P) {
  double a = 0;
  for (Eigen::Index i = 0; i < P.cols(); ++i) {
    const Vec<2> p = P.col(i), q = P.col((i + 1) % P.cols());
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

void checkOnZeroSet(const TriMesh& mesh, const ImplicitField<3>& field, double tol) {
  double worst = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) worst = std::max(worst, std::abs(field.value(mesh.vertices.col(v))));
  CHECK(worst <= tol);
}

}  // namespace

TEST_CASE("marching cubes: a sphere is a closed oriented manifold of genus 0") {
  const SphereField sphere(Vec<3>(0.05, -0.03, 0.02), 1.0);
  for (int resolution : {8, 24, 61}) {
    CAPTURE(resolution);
    MarchingReport report;
    const TriMesh mesh = marchingCubes(sphere, cube(1.3), {resolution, 6}, &report);
    const MeshCheck c = checkMesh(mesh);
    CHECK(c.closedManifold());
    CHECK(c.eulerCharacteristic == 2);
    CHECK(c.components == 1);
    CHECK(boundaryLoops(mesh).empty());
    // Outward: the enclosed volume is positive and close to 4π/3 (second-order in the cell size).
    const double h = 2.6 / resolution;
    CHECK(signedVolume(mesh) == doctest::Approx(4 * M_PI / 3).epsilon(2 * h * h));
    CHECK(countFlippedTriangles(mesh, mesh.normals) == 0);
    // The edge vertices are refined onto the zero set, except where the root lies within τ = 1e-3
    // of an edge's end (kept at τ: |f| ≤ τ·h for this distance field); polygon centres are off it.
    CHECK(report.maxAbsF <= 1e-3 * h);
    checkOnZeroSet(mesh, sphere, 0.1 * h * h + 1e-6);
    // Normals are ∇f: radial for a sphere.
    for (int v = 0; v < mesh.vertexCount(); ++v) {
      const Vec<3> radial = (mesh.vertices.col(v) - sphere.centre()).normalized();
      CHECK(mesh.normals.col(v).dot(radial) >= 1 - 1e-9);
    }
  }
}

namespace {

// tanh(k (‖x‖ − 1)): the unit sphere, with f nearly a step across a cell for large k, so that
// Newton along an edge starts where the slope is almost nil and false position converges slowly.
class SteepSphere final : public ImplicitField<3> {
 public:
  explicit SteepSphere(double k) : k_(k) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const double r = x.norm(), t = std::tanh(k_ * (r - 1));
    if (g) *g = k_ * (1 - t * t) * x / r;
    if (H) H->setZero();
    return t;
  }
  double lipschitzBound(const Box<3>&) const override { return k_; }

 private:
  double k_;
};

}  // namespace

TEST_CASE("marching cubes: edge vertices converge onto f = 0 where f bends sharply along the edge") {
  // At 24 cells over [−1.3, 1.3]³ a cell spans 0.108, about 5 units of tanh's argument.
  const SteepSphere steep(50);
  MarchingReport report;
  const TriMesh mesh = marchingCubes(steep, cube(1.3), {24}, &report);
  CHECK(checkMesh(mesh).closedManifold());
  CHECK(report.maxAbsF <= 1e-6);  // |f| ≤ 1e-6 is within 2e-8 of the sphere here
  for (int v = 0; v < mesh.vertexCount(); ++v) REQUIRE(std::abs(mesh.vertices.col(v).norm() - 1) <= 1e-6);
}

TEST_CASE("marching cubes: a torus is closed with Euler characteristic 0") {
  const TorusField torus;
  for (int resolution : {12, 40}) {
    CAPTURE(resolution);
    const TriMesh mesh = marchingCubes(torus, cube(1.1), {resolution});
    const MeshCheck c = checkMesh(mesh);
    CHECK(c.closedManifold());
    CHECK(c.eulerCharacteristic == 0);
    CHECK(c.components == 1);
    CHECK(signedVolume(mesh) > 0);
    CHECK(countFlippedTriangles(mesh, mesh.normals) == 0);
  }
}

TEST_CASE("marching cubes: ambiguous faces stay manifold and consistently oriented") {
  const GyroidField gyroid;
  for (int resolution : {5, 7, 13, 30}) {
    CAPTURE(resolution);
    const Box<3> box = cube(4.0);
    const TriMesh mesh = marchingCubes(gyroid, box, {resolution});
    const MeshCheck c = checkMesh(mesh);
    CHECK(mesh.triangleCount() > 0);
    CHECK(c.edgeManifold());
    CHECK(c.consistentlyOriented());
    CHECK(c.degenerateTriangles == 0);
    // The only boundary is where the surface leaves the box.
    for (const BoundaryLoop& loop : boundaryLoops(mesh))
      for (int v : loop) {
        const Vec<3> x = mesh.vertices.col(v);
        CHECK((x - box.lo).cwiseAbs().minCoeff() * (box.hi - x).cwiseAbs().minCoeff() <= 1e-12);
      }
  }
}

// f = xyz + a·x + b·y + c·z + d: on a single cube about the origin the corners' signs alternate
// (xyz dominates there) while a, b, c, d decide each face's saddle, so some choices chain one
// polygon through all twelve edges.
class SaddleField final : public ImplicitField<3> {
 public:
  explicit SaddleField(const Eigen::Vector4d& k) : k_(k) {}
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    if (g) *g = Vec<3>(x[1] * x[2] + k_[0], x[0] * x[2] + k_[1], x[0] * x[1] + k_[2]);
    if (H) *H << 0, x[2], x[1], x[2], 0, x[0], x[1], x[0], 0;
    return x[0] * x[1] * x[2] + k_[0] * x[0] + k_[1] * x[1] + k_[2] * x[2] + k_[3];
  }
  double lipschitzBound(const Box<3>&) const override { return 4; }  // ‖∇f‖ ≤ √3 (1 + 0.3) on [−1, 1]³

 private:
  Eigen::Vector4d k_;
};

TEST_CASE("marching cubes: polygons fanned around a centre have the centre on f = 0") {
  // Their centres start at the mean of the polygon, off the zero set, and move onto it inside
  // their cube (centre_vertices.h).
  const double values[] = {-0.3, -0.1, 0.1, 0.3};
  int centres = 0, offMean = 0;
  for (int i = 0; i < 512; ++i) {
    const Eigen::Vector4d k(values[i & 3], values[(i >> 2) & 3], values[(i >> 4) & 3], values[(i >> 6) & 3]);
    CAPTURE(k.transpose());
    const SaddleField field(k);
    MarchingOptions options{1};
    options.cull = i < 256;  // the streamed slabs, then the whole grid at once
    MarchingReport report;
    const TriMesh mesh = marchingCubes(field, cube(1.0), options, &report);
    centres += report.centreVertices;
    CHECK(report.centresOffZeroSet == 0);
    const int V = mesh.vertexCount();
    for (int v = V - report.centreVertices; v < V; ++v) {
      const Vec<3> x = mesh.vertices.col(v);
      Vec<3> g;
      CHECK(std::abs(field.evaluate(x, &g, nullptr)) <= 1e-12);
      CHECK(std::abs(mesh.normals.col(v).dot(g.normalized()) - 1) <= 1e-12);
      CHECK(x.cwiseAbs().maxCoeff() <= 1);  // inside its cube
      Vec<3> mean = Vec<3>::Zero();  // of the edge vertices of its fan
      int ring = 0;
      for (int t = 0; t < mesh.triangleCount(); ++t)
        for (int c = 0; c < 3; ++c)
          if (mesh.triangles(c, t) == v) mean += mesh.vertices.col(mesh.triangles((c + 1) % 3, t)), ++ring;
      offMean += std::abs(field.evaluate(mean / ring, nullptr, nullptr)) > 1e-3;
    }
    CHECK(checkMesh(mesh).edgeManifold());
    CHECK(checkMesh(mesh).consistentlyOriented());
  }
  CHECK(centres > 0);
  CHECK(offMean > 0);  // the means alone would have been off f = 0
}

// f = xy + 0.2 − 0.5·exp(−(x² + y²)/0.1): on [−1, 1]³ the faces z = ±1 have their corners (1, 1)
// and (−1, −1) outside, the other two inside, and the four values' bilinear saddle is +0.2
// (outside joined) while f there is −0.3: the inside joins along the cube's middle.
class PinchedSaddle final : public ImplicitField<3> {
 public:
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    const double e = 0.5 * std::exp(-(x[0] * x[0] + x[1] * x[1]) / 0.1);
    if (g) *g = Vec<3>(x[1] + 20 * x[0] * e, x[0] + 20 * x[1] * e, 0);
    if (H) H->setZero();  // unused here
    return x[0] * x[1] + 0.2 - e;
  }
  double lipschitzBound(const Box<3>&) const override { return 6; }
};

TEST_CASE("marching cubes: an ambiguous face is decided by f, not by its corners' bilinear interpolant") {
  const PinchedSaddle field;
  for (bool cull : {true, false}) {
    CAPTURE(cull);
    MarchingOptions options{1};
    options.cull = cull;
    const TriMesh mesh = marchingCubes(field, cube(1.0), options);
    REQUIRE(mesh.triangleCount() > 0);
    CHECK(checkMesh(mesh).edgeManifold());
    // Two pieces, each around an outside edge (x = y = ±1), not around the inside edges
    // (x = −y = ±1) as the bilinear decider joins them: every triangle's centroid has x·y > 0.
    for (int t = 0; t < mesh.triangleCount(); ++t) {
      const Vec<3> c = (mesh.vertices.col(mesh.triangles(0, t)) + mesh.vertices.col(mesh.triangles(1, t)) +
                        mesh.vertices.col(mesh.triangles(2, t))) / 3;
      CHECK(c[0] * c[1] > 0.1);
    }
  }
}

TEST_CASE("marching cubes: bad arguments are errors") {
  const SphereField sphere;
  CHECK_THROWS_AS(marchingCubes(sphere, cube(1), {0}), InputError);
  Box<3> flat = cube(1);
  flat.hi.z() = flat.lo.z();
  CHECK_THROWS_AS(marchingCubes(sphere, flat, {8}), InputError);
}

TEST_CASE("marching squares: a circle is one closed counter-clockwise polyline on the zero set") {
  const CircleField circle(Vec<2>(0.1, 0.05), 0.8);
  Box<2> box;
  box.lo = Vec<2>(-1, -1);
  box.hi = Vec<2>(1.2, 1);
  const std::vector<Polyline2d> lines = marchingSquares(circle, box, {40, 6});
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].closed);
  CHECK(signedArea(lines[0].points) == doctest::Approx(M_PI * 0.64).epsilon(1e-2));
  const double h = 2.2 / 40;  // |f| ≤ τ·h where the root is within τ = 1e-3 of an edge's end
  for (Eigen::Index i = 0; i < lines[0].points.cols(); ++i)
    CHECK(std::abs(circle.value(lines[0].points.col(i))) <= 1e-3 * h);
}

TEST_CASE("marching squares: near-touching circles give two separate closed curves") {
  const TwoCircles field;
  Box<2> box;
  box.lo = Vec<2>(-1.3, -0.8);
  box.hi = Vec<2>(1.3, 0.8);
  for (int resolution : {9, 13, 26, 101}) {
    CAPTURE(resolution);
    const std::vector<Polyline2d> lines = marchingSquares(field, box, {resolution});
    int closed = 0;
    for (const Polyline2d& l : lines) {
      closed += l.closed;
      CHECK(signedArea(l.points) > 0);
    }
    CHECK(closed == static_cast<int>(lines.size()));
    CHECK((lines.size() == 1 || lines.size() == 2));
  }
}

TEST_CASE("marching squares: a curve leaving the box is open") {
  const CircleField circle(Vec<2>(1.0, 0.0), 0.8);
  Box<2> box;
  box.lo = Vec<2>(-1, -1);
  box.hi = Vec<2>(1, 1);
  const std::vector<Polyline2d> lines = marchingSquares(circle, box, {20});
  REQUIRE(lines.size() == 1);
  CHECK_FALSE(lines[0].closed);
}

TEST_CASE("marching: culling far blocks gives exactly the dense result with fewer evaluations") {
  const SphereField sphere(Vec<3>(0.05, -0.03, 0.02), 0.7);
  const TorusField torus;
  const GyroidField gyroid;
  const HrbfModel<3> hrbf = fitHrbf<3>(makePreset3d("torus", 200), HrbfOptions{});
  struct Case {
    const ImplicitField<3>* field;
    double half;
    int resolution;
  };
  for (const Case& c : {Case{&sphere, 1.3, 61}, Case{&torus, 1.1, 40}, Case{&gyroid, 4.0, 13}, Case{&hrbf, 1.3, 50}}) {
    MarchingOptions dense{c.resolution};
    dense.cull = false;
    MarchingOptions culled{c.resolution};
    MarchingReport rd, rc;
    const TriMesh a = marchingCubes(*c.field, cube(c.half), dense, &rd);
    const TriMesh b = marchingCubes(*c.field, cube(c.half), culled, &rc);
    CHECK(a.triangles == b.triangles);
    CHECK(a.vertices == b.vertices);
    CHECK(rd.evaluatedPoints == rd.gridPoints);
    CHECK(rc.evaluatedPoints <= rc.gridPoints);
    MESSAGE("culling evaluated ", rc.evaluatedPoints, " of ", rc.gridPoints, " grid points");
  }
  const CircleField circle(Vec<2>(0.1, 0.05), 0.5);
  Box<2> box;
  box.lo = Vec<2>(-1, -1);
  box.hi = Vec<2>(1.2, 1);
  MarchingOptions dense{120};
  dense.cull = false;
  MarchingReport r2;
  const std::vector<Polyline2d> a = marchingSquares(circle, box, dense), b = marchingSquares(circle, box, {120}, &r2);
  REQUIRE(a.size() == b.size());
  CHECK(a[0].points == b[0].points);
  CHECK(r2.evaluatedPoints < r2.gridPoints / 2);
}
