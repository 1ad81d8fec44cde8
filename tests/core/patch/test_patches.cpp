#include <doctest/doctest.h>

#include <random>

#include "core/patch/bezier_patch.h"
#include "core/patch/patch_grid.h"
#include "core/patch/torus_patch_study.h"

using namespace hermite;

namespace {

HermitePatch randomPatch(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2, 2);
  HermitePatch h;
  for (auto& C : h.C)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) C(i, j) = u(rng);  // twists (rows/cols 1–2) non-zero
  return h;
}

}  // namespace

TEST_CASE("Hermite and Bézier forms of the same patch agree everywhere, twists included") {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 50; ++trial) {
    const HermitePatch h = randomPatch(rng);
    const BezierPatch b = toBezier(h);
    double scale = 0;
    for (const auto& C : h.C) scale = std::max(scale, C.cwiseAbs().maxCoeff());
    for (int a = 0; a <= 10; ++a)
      for (int c = 0; c <= 10; ++c) {
        const double s = a / 10.0, t = c / 10.0;
        const SurfacePoint ph = h.evaluate(s, t), pb = b.evaluate(s, t);
        CHECK((ph.X - pb.X).cwiseAbs().maxCoeff() <= 1e-12 * scale);
        CHECK((ph.Xs - pb.Xs).cwiseAbs().maxCoeff() <= 1e-12 * scale);
        CHECK((ph.Xt - pb.Xt).cwiseAbs().maxCoeff() <= 1e-12 * scale);
        CHECK((ph.Xst - pb.Xst).cwiseAbs().maxCoeff() <= 1e-12 * scale);
      }
    // Round trip Hermite → Bézier → Hermite is the identity.
    const HermitePatch back = toHermite(b);
    for (int k = 0; k < 3; ++k) CHECK((back.C[k] - h.C[k]).cwiseAbs().maxCoeff() <= 1e-13 * scale);
  }
}

TEST_CASE("a Hermite patch interpolates its corner points, tangents and twists") {
  std::mt19937 rng(3);
  const HermitePatch h = randomPatch(rng);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const SurfacePoint p = h.evaluate(a, b);
      CHECK((p.X - h.point(a, b)).norm() <= 1e-14);
      CHECK((p.Xs - h.sTangent(a, b)).norm() <= 1e-13);
      CHECK((p.Xt - h.tTangent(a, b)).norm() <= 1e-13);
      CHECK((p.Xst - h.twist(a, b)).norm() <= 1e-13);
    }
}

TEST_CASE("Bézier subdivision reproduces the patch on each half") {
  std::mt19937 rng(5);
  const BezierPatch b = toBezier(randomPatch(rng));
  const auto [lo, hi] = b.splitS(0.3);
  const auto [left, right] = b.splitT(0.6);
  for (double s : {0.0, 0.25, 0.5, 1.0})
    for (double t : {0.0, 0.4, 1.0}) {
      CHECK((lo.evaluate(s, t).X - b.evaluate(0.3 * s, t).X).norm() <= 1e-12);
      CHECK((hi.evaluate(s, t).X - b.evaluate(0.3 + 0.7 * s, t).X).norm() <= 1e-12);
      CHECK((left.evaluate(s, t).X - b.evaluate(s, 0.6 * t).X).norm() <= 1e-12);
      CHECK((right.evaluate(s, t).X - b.evaluate(s, 0.6 + 0.4 * t).X).norm() <= 1e-12);
    }
}

TEST_CASE("a patch grid is C¹ across shared edges") {
  const PatchGrid g({0.0, 0.4, 1.1, 1.5}, {0.0, 0.7, 1.0}, torusKnotData);
  const double eps = 1e-12;
  for (double v : {0.1, 0.35, 0.8}) {
    for (double uk : {0.4, 1.1}) {
      const SurfacePoint a = g.evaluate(uk - eps, v), b = g.evaluate(uk + eps, v);
      CHECK((a.X - b.X).norm() <= 1e-10);
      CHECK((a.Xs - b.Xs).norm() <= 1e-9);  // cross-boundary derivative
      CHECK((a.Xt - b.Xt).norm() <= 1e-9);
    }
  }
  // At the knots the grid reproduces the exact data.
  const SurfacePoint p = g.evaluate(0.4, 0.7);
  const KnotData d = torusKnotData(0.4, 0.7);
  CHECK((p.X - d.X).norm() <= 1e-13);
  CHECK((p.Xs - d.Xu).norm() <= 1e-12);
  CHECK((p.Xt - d.Xv).norm() <= 1e-12);
  CHECK((p.Xst - d.Xuv).norm() <= 1e-12);
  const auto tess = g.tessellate(5);
  CHECK(tess.positions.cols() == 6 * 25);
  CHECK(tess.triangles.cols() == 6 * 32);
  // Every tessellation vertex is the patch evaluated at its (s, t) — vertex (patch p, a, b) at
  // s = a/4, t = b/4 — with the unit normal Xs × Xt; triangles face that normal.
  for (int pi = 0; pi < 6; ++pi)
    for (int a = 0; a < 5; ++a)
      for (int b = 0; b < 5; ++b) {
        const SurfacePoint q = g.patch(pi / g.patchesV(), pi % g.patchesV()).evaluate(a / 4.0, b / 4.0);
        const int k = pi * 25 + a * 5 + b;
        CHECK((Vec<3>(tess.positions.col(k)) - q.X).norm() <= 1e-13);
        CHECK((Vec<3>(tess.normals.col(k)) - q.normal()).norm() <= 1e-12);
      }
  for (Eigen::Index t = 0; t < tess.triangles.cols(); ++t) {
    const Vec<3> a = tess.positions.col(tess.triangles(0, t)), b = tess.positions.col(tess.triangles(1, t)),
                 c = tess.positions.col(tess.triangles(2, t));
    CHECK((b - a).cross(c - a).dot(Vec<3>(tess.normals.col(tess.triangles(0, t)))) > 0);
  }
}

TEST_CASE("torus patch study: sanity anchors and decreasing error under refinement") {
  PatchStudyOptions o;
  const auto rows = torusPatchStudy(o);
  REQUIRE(rows.size() == 4);
  // DESIGN anchors: one patch on [0,1]²: ≈ 0.0717, 0.0396, 0.0114.
  CHECK(rows[0].error[0] == doctest::Approx(0.0717).epsilon(0.01));
  CHECK(rows[0].error[1] == doctest::Approx(0.0396).epsilon(0.01));
  CHECK(rows[0].error[2] == doctest::Approx(0.0114).epsilon(0.01));
  // Finer splits decrease the error; z = sin v does not depend on u, so splitting only u (2x1)
  // leaves its error unchanged (to rounding) while x and y drop.
  for (size_t i = 1; i < rows.size(); ++i) {
    for (int k = 0; k < 3; ++k) CHECK(rows[i].error[k] <= rows[i - 1].error[k] * (1 + 1e-12));
    CHECK(rows[i].error[0] + rows[i].error[1] + rows[i].error[2] <
          rows[i - 1].error[0] + rows[i - 1].error[1] + rows[i - 1].error[2]);
  }
  CHECK(rows[2].error[2] < rows[1].error[2]);
  for (const auto& r : rows) CHECK(r.hermiteBezierMaxDiff <= 1e-13);
  o.domain = {0, 0.5, 0, 0.5};
  o.splits = {{1, 1}};
  const auto half = torusPatchStudy(o);
  CHECK(half[0].error[0] == doctest::Approx(0.0053).epsilon(0.02));
  CHECK(half[0].error[1] == doctest::Approx(0.0014).epsilon(0.03));
  CHECK(half[0].error[2] == doctest::Approx(3.7e-4).epsilon(0.03));
}
