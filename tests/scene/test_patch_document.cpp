// The patch editor's document: presets, handles in both forms, and edits of the knot data.

#include <doctest/doctest.h>

#include "core/base/errors.h"
#include "core/patch/bezier_patch.h"
#include "scene/patch_document.h"
#include "scene/scene_file.h"

using namespace hermite;

namespace {

double maxControlDiff(const std::array<std::array<Vec<3>, 4>, 4>& a, const std::array<std::array<Vec<3>, 4>, 4>& b,
                      int skipP = -1, int skipQ = -1) {
  double d = 0;
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q)
      if (p != skipP || q != skipQ) d = std::max(d, (a[p][q] - b[p][q]).norm());
  return d;
}

// Largest jump of X and of the cross-boundary derivative across the grid's interior knot lines.
double c1Jump(const PatchGrid& g) {
  double jump = 0;
  const auto& u = g.uKnots();
  const auto& v = g.vKnots();
  for (int i = 1; i + 1 < int(u.size()); ++i)
    for (int j = 0; j + 1 < int(v.size()); ++j)
      for (double t : {0.0, 0.3, 0.71, 1.0}) {
        const double dv = v[j + 1] - v[j], du0 = u[i] - u[i - 1], du1 = u[i + 1] - u[i];
        const SurfacePoint left = g.patch(i - 1, j).evaluate(1.0, t), right = g.patch(i, j).evaluate(0.0, t);
        jump = std::max({jump, (left.X - right.X).norm(), (left.Xs / du0 - right.Xs / du1).norm()});
        (void)dv;
      }
  return jump;
}

}  // namespace

TEST_CASE("patch document: Bézier handles are the Bézier form of the grid's patches") {
  for (const auto& [preset, _] : patchPresets()) {
    CAPTURE(preset);
    PatchSpec s;
    s.preset = preset;
    s.splits = {3, 2};
    const PatchGrid g = buildPatchGrid(s);
    const auto knots = patchKnotData(s);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j) CHECK(maxControlDiff(patchControlPoints(s, knots, i, j), toBezier(g.patch(i, j)).P) < 1e-12);
  }
}

TEST_CASE("patch document: the saddle and flat presets are reproduced exactly") {
  PatchSpec s;
  s.preset = "saddle";
  s.splits = {2, 3};
  const PatchGrid g = buildPatchGrid(s);
  for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
    for (double v : {0.0, 0.4, 0.9}) {
      const Vec<3> X = g.evaluate(u, v).X;
      CHECK(X.z() == doctest::Approx(X.x() * X.y()).epsilon(1e-12).scale(1));
    }
  s.preset = "flat";
  CHECK(buildPatchGrid(s).evaluate(0.37, 0.61).X.z() == 0.0);
  s.preset = "nope";
  CHECK_THROWS_AS(buildPatchGrid(s), InputError);
}

TEST_CASE("patch document: a Bézier edit keeps the patch's other 15 control points and C¹ holds") {
  PatchSpec s;
  s.splits = {2, 2};
  s.form = PatchForm::Bezier;
  const auto before = patchKnotData(s);
  for (const auto& [p, q] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{0, 2}, std::pair{2, 2}, std::pair{3, 3}}) {
    CAPTURE(p);
    CAPTURE(q);
    const PatchHandle h{PatchHandle::Control, 1, 0, p, q};
    const Vec<3> target = patchHandlePosition(s, before, h) + Vec<3>(0.05, -0.1, 0.2);
    const PatchSpec moved = movePatchHandle(s, h, target);
    const auto c0 = patchControlPoints(s, before, 1, 0), c1 = patchControlPoints(moved, moved.knots, 1, 0);
    CHECK((c1[p][q] - target).norm() < 1e-12);
    CHECK(maxControlDiff(c0, c1, p, q) < 1e-12);
    CHECK(c1Jump(buildPatchGrid(moved)) < 1e-12);
  }
}

TEST_CASE("patch document: a Hermite tangent edit is the matching Bézier edit") {
  PatchSpec s;
  s.splits = {2, 1};
  const auto knots = patchKnotData(s);
  // The u-tangent handle of knot (1, 0): shared by patches (0, 0) and (1, 0).
  const PatchHandle h{PatchHandle::TangentU, 1, 0, 0, 0};
  const Vec<3> tip = patchHandlePosition(s, knots, h) + Vec<3>(0.02, 0.03, -0.04);
  const PatchSpec moved = movePatchHandle(s, h, tip);
  CHECK((moved.knots[1 * 2 + 0].Xu - knots[1 * 2 + 0].Xu).norm() > 0.1);
  CHECK(moved.knots[1 * 2 + 0].X == knots[1 * 2 + 0].X);
  // On uniform knots the tip is the control point next to the corner in the s direction: b10 of
  // patch (1, 0) — and its mirror b20 in patch (0, 0) moves oppositely (C¹).
  const auto right = patchControlPoints(moved, moved.knots, 1, 0), left = patchControlPoints(moved, moved.knots, 0, 0);
  CHECK((right[1][0] - tip).norm() < 1e-12);
  CHECK(((right[1][0] - right[0][0]) + (left[2][0] - left[3][0])).norm() < 1e-12);
  CHECK(c1Jump(buildPatchGrid(moved)) < 1e-12);
}

TEST_CASE("patch scenes: the document round-trips through the scene file; bad keys name their path") {
  const nlohmann::json doc = nlohmann::json::parse(R"({"version": 1, "mode": "patch",
      "patch": {"preset": "saddle", "splits": [2, 1], "form": "bezier"}})");
  Scene s = parseScene(doc, "p.json", ".");
  CHECK(s.patch.preset == "saddle");
  CHECK(s.patch.form == PatchForm::Bezier);
  s.patch = movePatchHandle(s.patch, PatchHandle{PatchHandle::Control, 1, 0, 1, 1}, Vec<3>(0.3, 0.2, 0.9));
  const Scene back = parseScene(sceneToJson(s), "p.json", ".");
  CHECK(back == s);
  const auto fails = [](const char* text) {
    try {
      parseScene(nlohmann::json::parse(text), "p.json", ".");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(fails(R"({"version": 1, "mode": "patch", "patch": {"splits": [0, 1]}})").find("patch.splits[0]") != std::string::npos);
  CHECK(fails(R"({"version": 1, "mode": "patch", "patch": {"preset": "cone"}})").find("patch.preset") != std::string::npos);
  CHECK(fails(R"({"version": 1, "mode": "patch", "patch": {"knots": []}})").find("patch.knots") != std::string::npos);
  CHECK(fails(R"({"version": 1, "mode": "patch", "patch": {"form": "nurbs"}})").find("patch.form") != std::string::npos);
}
