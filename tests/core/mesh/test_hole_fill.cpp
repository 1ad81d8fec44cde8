#include <doctest/doctest.h>

#include <chrono>
#include <cmath>

#include "core/base/errors.h"
#include "core/mesh/hole_fill.h"
#include "core/mesh/marching_cubes.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/mesh_shapes.h"
#include "core/shapes/presets.h"
#include "support/mesh_test_shapes.h"

using namespace hermite;
using hermite::testing::cutBall;
using hermite::testing::parametricTorus;
using hermite::testing::removeTriangles;
using hermite::testing::smallestAngleDegrees;

namespace {

Box<3> cube(double half) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-half);
  b.hi = Vec<3>::Constant(half);
  return b;
}

// Largest distance estimate |f| / ‖∇f‖ (exact for distance fields) over the vertices with id ≥ first.
double maxDistance(const TriMesh& mesh, const ImplicitField<3>& surface, int first) {
  double worst = 0;
  for (int v = first; v < mesh.vertexCount(); ++v) {
    Vec<3> g;
    const double f = surface.evaluate(mesh.vertices.col(v), &g);
    worst = std::max(worst, std::abs(f) / g.norm());
  }
  return worst;
}

// Unit ∇f of `surface` at every vertex (reference orientation for flipped triangles).
Eigen::Matrix3Xd fieldNormals(const TriMesh& mesh, const ImplicitField<3>& surface) {
  Eigen::Matrix3Xd n(3, mesh.vertexCount());
  for (int v = 0; v < mesh.vertexCount(); ++v) n.col(v) = surface.gradient(mesh.vertices.col(v)).normalized();
  return n;
}

double loopDiameter(const TriMesh& mesh, const BoundaryLoop& loop) {
  double d = 0;
  for (int a : loop)
    for (int b : loop) d = std::max(d, (mesh.vertices.col(a) - mesh.vertices.col(b)).norm());
  return d;
}

// Fills every hole of `holed` (cut from a closed mesh of Euler characteristic `chi`) and checks
// the result: closed oriented manifold, same χ, nothing flipped against ∇f of the true surface,
// new vertices within `relTol` × (largest hole diameter) of it, at most `unconvergedFraction` of
// the new vertices reported unconverged.
HoleFillResult fillAndCheck(const TriMesh& holed, const ImplicitField<3>& surface, int chi, double relTol,
                            const HoleFillOptions& options = {}, double unconvergedFraction = 0) {
  const std::vector<BoundaryLoop> loops = detectHoles(holed);
  double diameter = 0;
  for (const BoundaryLoop& l : loops) diameter = std::max(diameter, loopDiameter(holed, l));
  const HoleFillResult r = fillHoles(holed, options);
  CHECK(r.holesFound == static_cast<int>(loops.size()));
  CHECK(r.holesFilled == r.holesFound);
  for (const std::string& m : r.messages) MESSAGE(m);
  CHECK(r.unconverged <= unconvergedFraction * (r.mesh.vertexCount() - holed.vertexCount()));
  if (unconvergedFraction == 0) CHECK(r.messages.empty());
  const MeshCheck c = checkMesh(r.mesh);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == chi);
  CHECK(countFlippedTriangles(r.mesh, fieldNormals(r.mesh, surface)) == 0);
  const double dist = maxDistance(r.mesh, surface, holed.vertexCount());
  MESSAGE("holes ", loops.size(), ", diameter ", diameter, ": max distance of new vertices ", dist, " (",
          dist / diameter, " × diameter), max |f| of the fit ", r.maxAbsF, ", unconverged ", r.unconverged);
  CHECK(dist <= relTol * diameter);
  return r;
}

}  // namespace

TEST_CASE("hole filling: stages on a sphere hole, each returning its result") {
  const SphereField sphere;
  const TriMesh closed = marchingCubes(sphere, cube(1.3), {40});
  const TriMesh holed = cutBall(closed, Eigen::Vector3d(0, 0.6, 0.8), 0.3);
  const std::vector<BoundaryLoop> holes = detectHoles(holed);
  REQUIRE(holes.size() == 1);
  const PreparedMesh prepared(holed);

  const HolePatch front = advancingFront(prepared, holes[0]);
  REQUIRE(front.closed);
  CHECK(front.failure.empty());
  CHECK(front.vertices.cols() > 0);
  // Euler's formula for a disc: patch V (new + boundary) − E + F = 1.
  const int n = static_cast<int>(holes[0].size());
  const int F = static_cast<int>(front.triangles.cols()), K = static_cast<int>(front.vertices.cols());
  CHECK(F == 2 * K + n - 2);

  const HolePatch faired = fairPatch(prepared, front);
  CHECK(faired.triangles == front.triangles);
  // Fairing pulls the tangent-plane guesses toward the surface.
  double before = 0, after = 0;
  for (int k = 0; k < K; ++k) {
    before = std::max(before, std::abs(sphere.value(front.vertices.col(k))));
    after = std::max(after, std::abs(sphere.value(faired.vertices.col(k))));
  }
  MESSAGE("front max |f| ", before, ", faired ", after);

  for (HoleImplicitKind kind : {HoleImplicitKind::RbfOffset, HoleImplicitKind::Hrbf}) {
    HoleFillOptions o;
    o.implicit = kind;
    const HoleImplicit implicit = fitHoleImplicit(prepared, faired, o);
    CHECK(implicit.points.cols() > n);  // two rings
    for (Eigen::Index i = 0; i < implicit.points.cols(); ++i)
      CHECK(std::abs(implicit.field->value(implicit.points.col(i))) <= 1e-8);
    const ProjectionResult projected = projectPatch(prepared, faired, *implicit.field, o);
    CHECK(projected.unconverged == 0);
    CHECK(projected.maxAbsF <= 1e-9);
    double dist = 0;
    for (int k = 0; k < K; ++k) dist = std::max(dist, std::abs(sphere.value(projected.patch.vertices.col(k))));
    MESSAGE(std::string(kind == HoleImplicitKind::Hrbf ? "HRBF" : "RBF offset"), ": projected max distance to the sphere ", dist,
            " (hole diameter ", front.diameter, ")");
    // The HRBF gets the looser bound: the Hermite fit on two rings bends more inside the hole than
    // the RBF with offsets.
    CHECK(dist <= (kind == HoleImplicitKind::Hrbf ? 0.02 : 0.01) * front.diameter);
    CHECK(dist < after);
  }
}

TEST_CASE("hole filling: sphere with several holes") {
  const SphereField sphere;
  TriMesh m = marchingCubes(sphere, cube(1.3), {48});
  m = cutBall(m, Eigen::Vector3d(0, 0, 1), 0.35);
  m = cutBall(m, Eigen::Vector3d(1, 0, 0), 0.2);
  m = cutBall(m, Eigen::Vector3d(-0.6, -0.8, 0), 0.25);
  fillAndCheck(m, sphere, 2, 0.01);
  HoleFillOptions hrbf;
  hrbf.implicit = HoleImplicitKind::Hrbf;
  fillAndCheck(m, sphere, 2, 0.02, hrbf);
}

TEST_CASE("hole filling: non-convex holes on the inner side of a torus") {
  const TorusField torus;
  const TriMesh closed = parametricTorus(72, 36);
  // The inner equator (x = R − r) is a saddle region: the hole's boundary is not convex.
  const TriMesh inner = cutBall(closed, Eigen::Vector3d(0.4, 0, 0), 0.15);
  fillAndCheck(inner, torus, 0, 0.02);
  // Elongated across the inner side and the top.
  const TriMesh both = cutBall(cutBall(closed, Eigen::Vector3d(-0.42, 0, 0.1), 0.12), Eigen::Vector3d(0, 1.0, 0), 0.2);
  fillAndCheck(both, torus, 0, 0.02);
}

TEST_CASE("hole filling: the bunny (a marched HRBF of its point set)") {
  const HrbfModel<3> model = fitHrbf<3>(makePreset3d("bunny", 400), HrbfOptions{});
  Box<3> box;
  box.lo = model.centres().rowwise().minCoeff().array() - 0.1;
  box.hi = model.centres().rowwise().maxCoeff().array() + 0.1;
  const TriMesh closed = marchingCubes(model, box, {64});
  const MeshCheck c0 = checkMesh(closed);
  REQUIRE(c0.closedManifold());
  // Four holes spread over the surface, radius 3 % of the box diagonal (≈ 35 boundary edges).
  // The bunny's thin ears and sharp creases are where the front and the projection struggle:
  // a few unconverged vertices (left at their faired position, reported) are allowed.
  TriMesh holed = closed;
  const double size = (box.hi - box.lo).norm();
  for (int k : {2, 5, 8, 11}) holed = cutBall(holed, closed.vertices.col(closed.vertexCount() * k / 13), 0.03 * size);
  HoleFillOptions o;
  const HoleFillResult r = fillAndCheck(holed, model, c0.eulerCharacteristic, 0.06, o, 0.02);
  CHECK(r.holesFound == 4);
}

TEST_CASE("hole filling: pathological loops end, filled or reported") {
  const SphereField sphere;
  const TriMesh closed = marchingCubes(sphere, cube(1.3), {40});
  SUBCASE("figure-eight: two holes touching at a vertex") {
    const int centre = closed.triangles(0, 100);
    std::vector<int> fan;
    for (int t = 0; t < closed.triangleCount(); ++t)
      if ((closed.triangles.col(t).array() == centre).any()) fan.push_back(t);
    int second = -1;
    for (size_t k = 1; k < fan.size() && second < 0; ++k) {
      int shared = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) shared += closed.triangles(a, fan[0]) == closed.triangles(b, fan[k]);
      if (shared == 1) second = fan[k];
    }
    REQUIRE(second >= 0);
    const TriMesh eight = removeTriangles(closed, [&](int t) { return t == fan[0] || t == second; });
    const HoleFillResult r = fillHoles(eight);
    CHECK(r.holesFound == 2);
    CHECK(r.holesFilled == 2);
    CHECK(checkMesh(r.mesh).closedManifold());
  }
  SUBCASE("a long thin slit") {
    // Every triangle touching a thin slab over half the sphere: one long hole a few edges wide.
    const TriMesh slit = removeTriangles(closed, [&](int t) {
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d x = closed.vertices.col(closed.triangles(k, t));
        if (std::abs(x.z() - 0.2) < 0.01 && x.x() > 0) return true;
      }
      return false;
    });
    const auto t0 = std::chrono::steady_clock::now();
    const HoleFillResult r = fillHoles(slit);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(s < 10);
    CHECK(r.holesFound == 1);
    CHECK(r.holesFilled + static_cast<int>(r.messages.size()) >= 1);
    if (r.holesFilled == 1) {
      const MeshCheck c = checkMesh(r.mesh);
      CHECK(c.closed());
      CHECK(c.edgeManifold());
      CHECK(c.consistentlyOriented());
    }
  }
  SUBCASE("an open surface's outer rim is reported at once, not grown outward") {
    const int n = 100;  // a 100 × 100 grid: its rim (400 edges) turns −2π seen from the hole side
    TriMesh grid;
    grid.vertices.resize(3, (n + 1) * (n + 1));
    grid.triangles.resize(3, 2 * n * n);
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) grid.vertices.col(j * (n + 1) + i) = Eigen::Vector3d(double(i) / n, double(j) / n, 0);
    for (int j = 0, t = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = j * (n + 1) + i;
        grid.triangles.col(t++) = Eigen::Vector3i(a, a + 1, a + n + 2);
        grid.triangles.col(t++) = Eigen::Vector3i(a, a + n + 2, a + n + 1);
      }
    const auto t0 = std::chrono::steady_clock::now();
    const HoleFillResult r = fillHoles(grid);
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 2);
    CHECK(r.holesFound == 1);
    CHECK(r.holesFilled == 0);
    REQUIRE(r.messages.size() == 1);
    CHECK(r.messages[0].find("the rim of an open surface") != std::string::npos);
    REQUIRE(r.holes.size() == 1);
    CHECK(r.holes[0].method == "min-weight");  // 400 edges: past the front's limit
    CHECK_FALSE(r.holes[0].filled);
  }
  SUBCASE("a shallow bowl without its lid folds sharply at the rim but does not lie on itself: it closes") {
    // The lower 20° cap of the unit sphere: a new lid meets it at about 160°, past kRimDihedral,
    // while its centre stands 1 − cos 20° ≈ 0.06 above the bowl (9 % of the rim's diameter).
    const TriMesh ball = uvSphereMesh(64, 32);
    const double rimZ = -std::cos(20.0 * M_PI / 180.0);
    const TriMesh bowl = removeTriangles(ball, [&](int t) {
      for (int c = 0; c < 3; ++c)
        if (ball.vertices(2, ball.triangles(c, t)) > rimZ + 1e-9) return true;
      return false;
    });
    const HoleFillResult r = fillHoles(bowl);
    CHECK(r.holesFound == 1);
    CHECK(r.holesFilled == 1);
    for (const std::string& m : r.messages) MESSAGE(m);
    const MeshCheck c = checkMesh(r.mesh);
    CHECK(c.closedManifold());
    CHECK(c.eulerCharacteristic == 2);
    CHECK(smallestAngleDegrees(r.mesh, bowl.triangleCount()) >= 1.0);
    for (int v = bowl.vertexCount(); v < r.mesh.vertexCount(); ++v)  // the lid stays inside the sphere
      CHECK(r.mesh.vertices.col(v).norm() <= 1.0 + 1e-6);
  }
  SUBCASE("a flat sheet's rim is refused with the gap that shows the fill would lie on the sheet") {
    const TriMesh ball = uvSphereMesh(64, 32);
    TriMesh disc = removeTriangles(ball, [&](int t) {  // the lower cap, pressed flat
      for (int c = 0; c < 3; ++c)
        if (ball.vertices(2, ball.triangles(c, t)) > -std::cos(20.0 * M_PI / 180.0) + 1e-9) return true;
      return false;
    });
    disc.vertices.row(2).setZero();
    const HoleFillResult r = fillHoles(disc);
    CHECK(r.holesFilled == 0);
    REQUIRE(r.holes.size() == 1);
    CHECK(r.holes[0].reason.find("lies on it (90 % of its triangles within 0.0 %") != std::string::npos);
  }
  SUBCASE("a front bounded to too few steps ends at once; the minimum-weight fallback closes the hole") {
    HoleFillOptions o;
    o.frontStepFactor = 0;
    const HoleFillResult r = fillHoles(cutBall(closed, Eigen::Vector3d(0, 0, 1), 0.5), o);
    CHECK(r.holesFound == 1);
    CHECK(r.holesFilled == 1);
    REQUIRE(r.holes.size() == 1);
    CHECK(r.holes[0].method == "min-weight");
    CHECK(r.holes[0].reason.empty());
    CHECK(checkMesh(r.mesh).closedManifold());
  }
}

TEST_CASE("hole filling: a triangle soup's lone triangles are reported, not doubled") {
  TriMesh soup;
  soup.vertices.resize(3, 6);
  soup.vertices << 0, 1, 0, 2, 3, 2,  //
      0, 0, 1, 0, 0, 1,               //
      0, 0, 0, 0, 0, 0;
  soup.triangles.resize(3, 2);
  soup.triangles << 0, 3,  //
      1, 4,                //
      2, 5;
  const HoleFillResult r = fillHoles(soup);
  CHECK(r.holesFound == 2);
  CHECK(r.holesFilled == 0);
  CHECK(r.trianglesAdded == 0);
  CHECK(r.messages.size() == 2);
  CHECK(r.mesh.triangleCount() == 2);
}

TEST_CASE("hole filling: bad options are input errors; a closed mesh is returned unchanged") {
  const TriMesh closed = parametricTorus(24, 12);
  HoleFillOptions o;
  o.rings = 0;
  CHECK_THROWS_AS(fillHoles(closed, o), InputError);
  const HoleFillResult r = fillHoles(closed);
  CHECK(r.holesFound == 0);
  CHECK(r.mesh.triangles == closed.triangles);
  CHECK(r.mesh.vertices == closed.vertices);
}
