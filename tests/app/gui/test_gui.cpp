// Scripted headless UI tests (docs/design.md, Testing): the application on an OSMesa context,
// driven frame by frame with FrameInput (mouse position, buttons, keys), checking the document,
// the fit and the undo history.

#include <doctest/doctest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <imgui.h>

#include "app/gui/gui_app.h"
#include "app/gui/input_queue.h"
#include "app/gui/scene_view.h"
#include "io/mesh_file.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"
#include "scene/scene_file.h"
#include "scene/hole_fill_stages.h"
#include "scene/scene_fit.h"
#include "support/gui_harness.h"
#include "support/mesh_test_shapes.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "support/timing_slack.h"

using namespace hermite;
using namespace hermite::app;
using hermite::app::testing::Harness;

namespace {

Scene scene2d(int count = 24) {
  Scene s;
  s.mode = SceneMode::Implicit2d;
  s.data.preset = "curve2d";
  s.data.count = count;
  s.fit.kernel = KernelType::Cubic;
  s.sourceName = "test-2d";
  return s;
}

// scene2d with a kernel whose radius matters: Gaussian, r = 0.3.
Scene gaussianScene2d() {
  Scene s = scene2d();
  s.fit.kernel = KernelType::Gaussian;
  s.fit.radius = 0.3;
  return s;
}

Scene scene3d(const std::string& preset = "sphere", int count = 40) {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = preset;
  s.data.count = count;
  s.view.size = {320, 240};
  s.sourceName = "test-3d";
  return s;
}

}  // namespace

TEST_CASE("UI: dragging a 2D sample moves it and the field is refitted through its new position") {
  Harness h(scene2d());
  h.frames(2);
  REQUIRE(h.app->shownFit() != nullptr);
  const int i = 3;
  const auto p = h.app->sampleScreenPosition(i);
  REQUIRE(p);
  const Vec<2> origin = h.app->viewOrigin();
  const Vec<2> from = *p + origin, to = from + Vec<2>(25, -18);
  // A drag on an unselected sample pans (the viewer convention): the sample stays put.
  h.drag(from.x(), from.y(), to.x(), to.y());
  CHECK(h.app->selectedSample() == -1);
  CHECK(h.app->document().scene().data == scene2d().data);
  CHECK(!h.app->document().canUndo());
  h.key(GLFW_KEY_HOME);  // the pan undone
  REQUIRE(h.app->document().scene() == scene2d());
  h.click(from.x(), from.y());  // a click selects
  REQUIRE(h.app->selectedSample() == i);
  h.drag(from.x(), from.y(), to.x(), to.y());  // dragging the selection moves it
  CHECK(h.app->selectedSample() == i);
  const Scene& s = h.app->document().scene();
  REQUIRE(s.data.isInline());  // the first edit wrote the preset's samples into the scene
  // Where the sample went, in world coordinates, and the refitted field vanishes there.
  const View2d view = sceneView2d(s, h.app->viewResult().width, h.app->viewResult().height);
  const Vec<2> expected = view.pixelToWorld(to.x() - origin.x(), to.y() - origin.y());
  const Vec<2> moved(s.data.points[i][0], s.data.points[i][1]);
  CHECK((moved - expected).norm() < 1e-9);
  REQUIRE(h.app->shownVersion() == h.app->document().version());
  const FitOutcome* fit = h.app->shownFit();
  REQUIRE(fit->as<SceneFit<2>>());
  CHECK(std::abs(fit->as<SceneFit<2>>()->field().value(moved)) < 1e-9);
  // One undo step for the whole drag, and it restores the exact previous document.
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == scene2d());
  h.key(GLFW_KEY_Z, true, true);  // redo
  CHECK(h.app->document().scene().data.points[i][0] == moved.x());
}

TEST_CASE("UI: Ctrl+Shift+drag moves any sample without selecting it first") {
  Harness h(scene2d());
  h.frames(2);
  const int i = 7;
  const Vec<2> from = *h.app->sampleScreenPosition(i) + h.app->viewOrigin(), to = from + Vec<2>(-20, 15);
  h.input.ctrl = h.input.shift = true;
  h.drag(from.x(), from.y(), to.x(), to.y());
  h.input.ctrl = h.input.shift = false;
  CHECK(h.app->selectedSample() == i);
  const Scene& s = h.app->document().scene();
  REQUIRE(s.data.isInline());
  CHECK(s.data.points.size() == 24);  // moved, not added
  const Vec<2> moved(s.data.points[i][0], s.data.points[i][1]);
  const View2d view = sceneView2d(s, h.app->viewResult().width, h.app->viewResult().height);
  const Vec<2> origin = h.app->viewOrigin();
  CHECK((moved - view.pixelToWorld(to.x() - origin.x(), to.y() - origin.y())).norm() < 1e-9);
}

TEST_CASE("UI: dragging the normal's tip rotates the normal; N flips it; Del deletes; undo restores each") {
  Harness h(scene2d());
  h.frames(2);
  const Vec<2> origin = h.app->viewOrigin();
  const int i = 5;
  h.click(h.app->sampleScreenPosition(i)->x() + origin.x(), h.app->sampleScreenPosition(i)->y() + origin.y());
  REQUIRE(h.app->selectedSample() == i);
  const Scene before = h.app->document().scene();
  const Vec<2> tip = *h.app->normalTipScreenPosition(i) + origin;
  const Vec<2> p = *h.app->sampleScreenPosition(i) + origin;
  // Drag the tip a quarter turn around the sample (screen y points down).
  const Vec<2> d = tip - p;
  const Vec<2> rotated = p + Vec<2>(-d.y(), d.x());
  h.drag(tip.x(), tip.y(), rotated.x(), rotated.y());
  const Scene& s = h.app->document().scene();
  const auto& n = s.data.normals[i];
  // The new normal points at the dragged tip: world direction = screen direction with y flipped.
  const Vec<2> want = Vec<2>(rotated.x() - p.x(), -(rotated.y() - p.y())).normalized();
  CHECK(Vec<2>(n[0], n[1]).dot(want) > 1 - 1e-9);
  CHECK(h.app->shownFit()->as<SceneFit<2>>()->field().gradient(Vec<2>(s.data.points[i][0], s.data.points[i][1])).normalized().dot(want) >
        1 - 1e-6);
  const Scene afterRotate = s;
  h.key(GLFW_KEY_N);
  CHECK(h.app->document().scene().data.normals[i][0] == -afterRotate.data.normals[i][0]);
  h.key(GLFW_KEY_DELETE);
  CHECK(h.app->document().scene().data.points.size() == afterRotate.data.points.size() - 1);
  h.key(GLFW_KEY_Z, true);
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == afterRotate);
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == before);
}

TEST_CASE("UI: the r slider changes the radius, refits, and is one undo step") {
  const Scene s = gaussianScene2d();
  Harness h(s);
  h.frames(2);
  const auto rect = h.app->widgetRect("fit.radius");
  REQUIRE(rect);
  const double y = 0.5 * ((*rect)[1] + (*rect)[3]);
  // Drag the slider's grab towards the right end: a larger radius (logarithmic slider).
  h.drag((*rect)[0] + 0.55 * ((*rect)[2] - (*rect)[0]), y, (*rect)[0] + 0.8 * ((*rect)[2] - (*rect)[0]), y);
  const double r = h.app->document().scene().fit.radius;
  CHECK(r > 0.3);
  REQUIRE(h.app->shownFit());
  CHECK(h.app->shownFit()->scene.fit.radius == r);
  CHECK(h.app->shownVersion() == h.app->document().version());
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == s);
}

TEST_CASE("UI: arrow keys over the r slider nudge r by 5 %, with Shift by 0.5 %, one undo step each") {
  const Scene s = gaussianScene2d();
  Harness h(s);
  h.frames(2);
  const auto rect = h.app->widgetRect("fit.radius");
  REQUIRE(rect);
  h.moveTo(0.5 * ((*rect)[0] + (*rect)[2]), 0.5 * ((*rect)[1] + (*rect)[3]));
  h.key(GLFW_KEY_RIGHT);
  CHECK(h.app->document().scene().fit.radius == doctest::Approx(0.3 * 1.05).epsilon(1e-12));
  h.key(GLFW_KEY_LEFT, false, true);
  CHECK(h.app->document().scene().fit.radius == doctest::Approx(0.3 * 1.05 / 1.005).epsilon(1e-12));
  h.key(GLFW_KEY_Z, true);
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene().fit.radius == 0.3);
}

TEST_CASE("UI: view-only changes redraw without a refit; a fit setting refits") {
  Harness h(scene3d(), true, 640, 480);
  h.frames(2);
  const FitOutcome* fitted = h.app->shownFit();
  REQUIRE(fitted);
  REQUIRE(h.app->viewIsCurrent());
  // A display checkbox (points off), then the camera: new document versions, the same fit.
  Scene s = h.app->document().scene();
  s.view.showPoints = false;
  h.app->document().apply(s, "points");
  h.frames(2);
  CHECK(h.app->shownFit() == fitted);
  CHECK(h.app->viewIsCurrent());
  const Vec<2> o = h.app->viewOrigin();
  const Vec<2> start(o.x() + 30, o.y() + h.app->viewSize().y() - 60);
  h.drag(start.x(), start.y(), start.x() + 60, start.y() - 10);  // orbit
  h.frames(4);
  CHECK(h.app->document().scene().view.camera != s.view.camera);
  CHECK(h.app->shownFit() == fitted);
  CHECK(h.app->viewIsCurrent());
  CHECK(h.app->shownVersion() == h.app->document().version());
  // A fit setting: a new fit, of the new setting.
  s = h.app->document().scene();
  s.fit.smoothing = 1e-6;
  h.app->document().apply(s, "smoothing");
  h.frames(2);
  REQUIRE(h.app->shownFit());
  CHECK(h.app->shownFit() != fitted);
  CHECK(h.app->shownFit()->scene.fit.smoothing == 1e-6);
  CHECK(h.app->viewIsCurrent());
}

TEST_CASE("UI: ticking the bounds box or the partition boxes redraws and submits no fit; r submits one") {
  Harness h(scene3d(), true, 1000, 1000);  // tall enough for the whole View panel
  h.frames(2);
  const FitOutcome* fitted = h.app->shownFit();
  REQUIRE(fitted);
  const int submitted = h.app->fitSubmissions();
  const ConcernVersions v0 = h.app->document().versions();
  const auto box = h.app->widgetRect("view.bounds_box");
  REQUIRE(box);
  h.click(0.5 * ((*box)[0] + (*box)[2]), 0.5 * ((*box)[1] + (*box)[3]));
  h.frames(2);
  CHECK(h.app->document().scene().view.showBounds);
  CHECK(h.app->document().versions().view > v0.view);
  CHECK(h.app->document().versions().fitInputs() == v0.fitInputs());
  CHECK(h.app->fitSubmissions() == submitted);
  CHECK(h.app->shownFit() == fitted);
  CHECK(h.app->viewIsCurrent());  // redrawn with the same fit
  // An overlay outside the document: not even a new document version.
  const std::uint64_t version = h.app->document().version();
  const auto overlay = h.app->widgetRect("view.partition_boxes");
  REQUIRE(overlay);
  h.click(0.5 * ((*overlay)[0] + (*overlay)[2]), 0.5 * ((*overlay)[1] + (*overlay)[3]));
  h.frames(2);
  CHECK(h.app->document().version() == version);
  CHECK(h.app->fitSubmissions() == submitted);
  // A fit setting: exactly one new fit.
  Scene s = h.app->document().scene();
  s.fit.radius *= 1.5;
  h.app->document().apply(s, "radius");
  h.frames(2);
  CHECK(h.app->fitSubmissions() == submitted + 1);
  CHECK(h.app->shownFit() != fitted);
}

TEST_CASE("UI: a click recorded during a slow frame lands where it happened, not where the mouse went after") {
  Harness h(scene3d(), true, 1000, 1000);
  h.frames(2);
  const auto box = h.app->widgetRect("view.bounds_box");
  REQUIRE(box);
  const CameraSpec camera = h.app->document().scene().view.camera;
  const Vec<2> o = h.app->viewOrigin();
  // During one frame of 2 s: to the checkbox, press, release, then on into the view.
  InputQueue queue;
  const auto at = [](double t, double x, double y) {
    InputEvent e;
    e.time = t;
    e.x = x;
    e.y = y;
    return e;
  };
  const auto left = [](double t, bool down) {
    InputEvent e;
    e.kind = InputEvent::Kind::Button;
    e.time = t;
    e.down = down;
    return e;
  };
  queue.push(at(0.1, 0.5 * ((*box)[0] + (*box)[2]), 0.5 * ((*box)[1] + (*box)[3])));
  queue.push(left(0.2, true));
  queue.push(left(0.25, false));
  queue.push(at(1.5, o.x() + 200, o.y() + 200));
  queue.push(at(1.9, o.x() + 260, o.y() + 220));
  // The frame after the slow one takes them in order (the old per-frame snapshot saw the press at
  // the last position, in the view, and orbited or selected there).
  h.replay(queue);
  h.frames(2);
  CHECK(h.app->document().scene().view.showBounds);  // the click toggled the checkbox
  CHECK(h.app->document().scene().view.camera == camera);  // and did not orbit the view
  CHECK(h.app->selectedSample() == -1);
}

TEST_CASE("UI: orbit, zoom and fit-to-view move the 3D camera and never touch the undo history") {
  Harness h(scene3d(), true, 640, 480);
  h.frames(2);
  const CameraSpec c0 = h.app->document().scene().view.camera;
  const Vec<2> o = h.app->viewOrigin();
  // The lower left corner of the view is empty: the sphere's samples sit in the middle, and the
  // Diagnostics window (top right, as wide as its text, which holds timings) can reach the top left.
  const Vec<2> start(o.x() + 30, o.y() + h.app->viewSize().y() - 60);
  h.moveTo(start.x(), start.y());
  REQUIRE(!ImGui::GetIO().WantCaptureMouse);
  h.drag(start.x(), start.y(), start.x() + 80, start.y() - 20);  // orbit
  const CameraSpec c1 = h.app->document().scene().view.camera;
  CHECK(c1.eye != c0.eye);
  const auto dist = [](const CameraSpec& c) {
    return std::hypot(c.eye[0] - c.target[0], c.eye[1] - c.target[1], c.eye[2] - c.target[2]);
  };
  CHECK(dist(c1) == doctest::Approx(dist(c0)).epsilon(1e-9));  // orbiting keeps the distance
  h.input.wheel = 2;
  h.moveTo(o.x() + 150, o.y() + 200);
  CHECK(dist(h.app->document().scene().view.camera) < dist(c1));
  CHECK(!h.app->document().canUndo());
  h.key(GLFW_KEY_HOME);
  CHECK(h.app->document().scene().view.camera == c0);
}

TEST_CASE("UI: Alt + drag moves the slice plane along its normal, as one undo step, without orbiting") {
  Scene s = scene3d();
  s.view.slice.enabled = true;
  s.view.slice.normal = {1, 0, 0};
  s.view.slice.offset = 0;
  Harness h(s, true, 640, 480);
  h.frames(2);
  const CameraSpec camera = h.app->document().scene().view.camera;
  const Vec<2> o = h.app->viewOrigin();
  const Vec<2> size = h.app->viewSize();
  const Vec<2> c = o + 0.5 * size;
  // The world x of the plane point under the cursor, 80 px right of the centre (the camera looks
  // down −z with x to the right): the plane follows the mouse there.
  const Camera cam = sceneCamera(h.app->document().scene(), int(size.x()), int(size.y()));
  const Ray ray = cam.ray(0.5 * size.x() + 80, 0.5 * size.y());
  const double expected = ray.at(-ray.origin.z() / ray.direction.z()).x();
  h.input.alt = true;
  h.drag(c.x(), c.y(), c.x() + 80, c.y());
  h.input.alt = false;
  h.frame();
  const SliceSpec& moved = h.app->document().scene().view.slice;
  CHECK(moved.offset == doctest::Approx(expected).epsilon(0.02));
  CHECK(h.app->document().scene().view.camera == camera);  // no orbit
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene().view.slice.offset == 0.0);
  CHECK(!h.app->document().canUndo());
}

TEST_CASE("UI: with the slice normal along the view direction, Alt + vertical drag moves the plane") {
  Scene facing = scene3d();
  facing.view.slice.enabled = true;
  facing.view.slice.normal = {0, 0, 1};
  Harness f(facing, true, 640, 480);
  f.frames(2);
  const Vec<2> o = f.app->viewOrigin();
  const Vec<2> c = o + 0.5 * f.app->viewSize();
  f.input.alt = true;
  f.drag(c.x(), c.y(), c.x(), o.y() + 2, 10);  // up to the top of the view
  f.input.alt = false;
  f.frame();
  const double offset = f.app->document().scene().view.slice.offset;
  CHECK(offset > 0.3);
  CHECK(offset <= 3.0);
  CHECK(f.app->document().scene().view.camera == facing.view.camera);  // no orbit
}

TEST_CASE("UI: every panel renders, with the explorer, the compare view and the help overlay") {
  Harness h(scene3d("two-tori", 60), true, 1100, 760);
  h.app->panels.compare = true;
  h.app->panels.explore = true;
  h.app->panels.help = true;
  h.app->compare.enabled = true;
  h.frames(3);
  REQUIRE(h.app->shownFit());
  CHECK(h.app->status().error == false);
  h.app->explorer().start(h.app->document().scene(), logSpacedRadii(0.2, 2.0, 3));
  h.app->explorer().wait();
  h.frames(2);
  CHECK(h.app->explorer().entries().size() == 3);
  CHECK(h.app->viewResult().width == (1100 - int(kLeftPanelWidth)) / 2);
  CHECK(h.app->glyphMisses() == 0);  // every character of every panel is in the UI font
}

TEST_CASE("UI: during a fit of about a second frames keep coming, and Cancel keeps the previous result") {
  Harness h(scene3d("sphere", 60), false, 640, 480);
  // The first fit (small) arrives, and its view is baked and refined (on the view worker: the
  // frames below measure a fit alone, as they did when the view was drawn in the frame the fit
  // arrived in). A deadline, not a frame count: the view worker runs at nice 10, and beside other
  // tests on both cores its first settled view can take many seconds (a hang guard only).
  const auto settleBy = std::chrono::steady_clock::now() + std::chrono::duration<double>(90 * hermite::testing::kTimingSlack);
  while (!(h.app->shownFit() && h.app->viewIsCurrent()) && std::chrono::steady_clock::now() < settleBy) {
    h.frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE(h.app->shownFit());
  REQUIRE(h.app->viewIsCurrent());
  const std::uint64_t good = h.app->shownVersion();
  // A large fit: 1500 samples (6000 unknowns, dense) outlasts many frames, so the test sees it running.
  Scene big = h.app->document().scene();
  big.data.count = 1500;
  h.app->document().apply(big, "count");
  h.frame();
  REQUIRE(h.app->worker().busy());
  double slowest = 0;
  int frames = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (h.app->worker().runningMs() < 300 && frames < 1000) {
    const auto f0 = std::chrono::steady_clock::now();
    h.frame();
    slowest = std::max(slowest, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - f0).count());
    ++frames;
  }
  CHECK(frames >= 3);
  CHECK(slowest < 250);  // the UI keeps drawing while the worker fits
  (void)t0;
  // Press Cancel in the diagnostics panel.
  const auto cancel = h.app->widgetRect("diagnostics.cancel");
  REQUIRE(cancel);
  h.click(0.5 * ((*cancel)[0] + (*cancel)[2]), 0.5 * ((*cancel)[1] + (*cancel)[3]));
  CHECK(h.app->status().message.find("cancelled") != std::string::npos);
  h.app->worker().waitIdle(120);
  h.frames(3);
  CHECK(h.app->shownVersion() == good);  // the cancelled fit never replaces the shown one
  CHECK(h.app->shownFit()->as<SceneFit<3>>()->samples.size() < 1500);
}

TEST_CASE("UI: dragging a patch tangent handle edits the knot data; the Bézier form shows the same edit") {
  Scene s;
  s.mode = SceneMode::Patch;
  s.data.preset = "sphere6";
  s.patch.splits = {2, 1};
  s.view.camera.eye = {5, 3.5, 3.5};
  s.view.camera.target = {2.2, 1.3, 0.4};
  s.view.camera.up = {0, 0, 1};
  Harness h(s, true, 1000, 700);
  h.frames(2);
  REQUIRE(h.app->shownFit());
  REQUIRE(h.app->shownFit()->as<PatchDisplay>());
  // The u-tangent handle of the middle knot (1, 0), shared by both patches.
  const PatchHandle tangent{PatchHandle::TangentU, 1, 0, 0, 0};
  const auto at = h.app->patchHandleScreenPosition(tangent);
  REQUIRE(at);
  const Vec<2> from = *at + h.app->viewOrigin(), to = from + Vec<2>(30, -20);
  const auto before = patchKnotData(s.patch);
  h.drag(from.x(), from.y(), to.x(), to.y());
  const PatchSpec& edited = h.app->document().scene().patch;
  REQUIRE(edited.knots.size() == before.size());
  CHECK(edited.knots[2].X == before[2].X);                   // the point stays
  CHECK((edited.knots[2].Xu - before[2].Xu).norm() > 0.05);  // the tangent moved
  for (std::size_t k : {0u, 1u, 3u, 4u, 5u}) CHECK(edited.knots[k].Xu == before[k].Xu);
  // The handle ended under the mouse (on the plane through it facing the camera).
  const auto now = h.app->patchHandleScreenPosition(tangent);
  REQUIRE(now);
  CHECK((*now + h.app->viewOrigin() - to).norm() < 0.5);
  // The other form: switching to Bézier does not change the surface, and patch (1, 0)'s control
  // point b10 sits where the Hermite tip was dragged (uniform knots: the tip is b10).
  Scene bezier = h.app->document().scene();
  bezier.patch.form = PatchForm::Bezier;
  h.app->document().apply(bezier, "form");
  h.frames(2);
  const PatchHandle b10{PatchHandle::Control, 1, 0, 1, 0};
  const auto control = h.app->patchHandleScreenPosition(b10);
  REQUIRE(control);
  CHECK((*control + h.app->viewOrigin() - to).norm() < 0.5);
  CHECK(h.app->shownFit()->as<PatchDisplay>()->mesh.positions.isApprox(buildPatchDisplay(edited).mesh.positions, 1e-14));
  // Undo twice: the form, then the drag — the original document.
  h.key(GLFW_KEY_Z, true);
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == s);
}

TEST_CASE("UI: a partition-of-unity fit shows its boxes; Flip all normals is one undoable edit") {
  Scene s = scene2d(120);
  s.fit.partition.enabled = PartitionSwitch::On;
  s.fit.partition.maxPointsPerBox = 10;
  Harness h(s, true, 1000, 700);
  h.frames(2);
  REQUIRE(h.app->shownFit());
  REQUIRE(h.app->shownFit()->as<SceneFit<2>>());
  REQUIRE(h.app->shownFit()->as<SceneFit<2>>()->pu());
  const ImageRgba8 without = h.target->read();
  const auto box = h.app->widgetRect("view.partition_boxes");
  REQUIRE(box);
  h.click(0.5 * ((*box)[0] + (*box)[2]), 0.5 * ((*box)[1] + (*box)[3]));
  h.frames(1);
  const ImageRgba8 with = h.target->read();
  int changed = 0;
  for (int j = 0; j < with.height; ++j)
    for (int i = int(kLeftPanelWidth) + 1; i < with.width; ++i) changed += std::memcmp(with.at(i, j), without.at(i, j), 3) != 0;
  CHECK(changed > 500);  // the box lines over the view

  const auto flip = h.app->widgetRect("data.flip_all");
  REQUIRE(flip);
  h.click(0.5 * ((*flip)[0] + (*flip)[2]), 0.5 * ((*flip)[1] + (*flip)[3]));
  const Scene& flipped = h.app->document().scene();
  REQUIRE(flipped.data.isInline());
  std::vector<std::string> warnings;
  const Scene original = withInlineSamples<2>(s, warnings);
  for (std::size_t k = 0; k < flipped.data.normals.size(); ++k) CHECK(flipped.data.normals[k][0] == -original.data.normals[k][0]);
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == s);
}

TEST_CASE("UI: the transform gizmo translates and rotates the fitted model by coefficient updates") {
  Scene s = scene3d("sphere", 40);
  s.view.camera.eye = {2.5, 2.0, 3.5};
  Harness h(s, true, 1000, 700);
  h.app->setGizmoVisible(true);
  h.frames(2);
  REQUIRE(h.app->shownFit());
  const Vec<2> o = h.app->viewOrigin();
  const Camera cam = sceneCamera(h.app->document().scene(), 1000 - int(kLeftPanelWidth), 700 - int(kStatusBarHeight));
  const auto shownCentroid = [&] { return Vec<3>(h.app->shownFit()->as<SceneFit<3>>()->data.points.rowwise().mean()); };
  const Vec<3> c0 = shownCentroid();
  // The x arrow starts at the pivot (the centroid) along +x: grab it 40 px out, pull along it.
  const Vec<2> dir = (cam.project(Vec<3>(c0 + Vec<3>(0.3, 0, 0))) - cam.project(c0)).normalized();
  const Vec<2> grab = cam.project(c0) + 40 * dir + o;
  h.drag(grab.x(), grab.y(), grab.x() + 60 * dir.x(), grab.y() + 60 * dir.y());
  const TransformSpec& t = h.app->document().scene().transform;
  REQUIRE(t.translate.size() == 3);
  CHECK(t.translate[0] > 0.05);
  CHECK(std::abs(t.translate[1]) < 1e-12);
  CHECK(std::abs(t.translate[2]) < 1e-12);
  const FitOutcome* f = h.app->shownFit();
  REQUIRE(f->as<SceneFit<3>>()->transformed);
  CHECK(f->as<SceneFit<3>>()->transform.method == "coefficient-update");
  CHECK(fitResiduals(*f->as<SceneFit<3>>()).maxAbsF < 1e-9);  // the updated model interpolates the moved data
  CHECK((shownCentroid() - c0 - Vec<3>(t.translate[0], 0, 0)).norm() < 1e-9);
  // Switching the model to the re-solve keeps the transform and refits.
  Scene resolve = h.app->document().scene();
  resolve.transform.method = TransformMethod::Resolve;
  resolve.transform.verify = true;
  h.app->document().apply(resolve, "model");
  h.frames(2);
  CHECK(h.app->shownFit()->as<SceneFit<3>>()->transform.method == "re-solve");
  REQUIRE(h.app->shownFit()->as<SceneFit<3>>()->transform.maxAbsDf);
  CHECK(*h.app->shownFit()->as<SceneFit<3>>()->transform.maxAbsDf < 1e-8);  // exact conditions: update == re-solve
  h.key(GLFW_KEY_Z, true);
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene() == s);
}

TEST_CASE("UI: right after a mode switch the previous mode's fit stays on screen and nothing reads it as the new one") {
  Harness h(scene3d("sphere", 40), true, 900, 600);
  h.frames(2);
  REQUIRE(h.app->shownFit()->as<SceneFit<3>>());
  // Switch to 2D outside the panels: the next frame draws the panels before the new fit runs.
  h.app->document().apply(scene2d(), "to 2D");
  h.frame();
  REQUIRE(h.app->shownFit()->as<SceneFit<2>>());
  h.key(GLFW_KEY_DELETE);  // no sample selected: nothing happens, nothing crashes
  Scene patch = h.app->document().scene();
  patch.mode = SceneMode::Patch;
  h.app->document().apply(patch, "to patch");
  CHECK(h.app->currentFit() == nullptr);  // the 2D fit is still shown but is not the patch's
  h.frame();
  REQUIRE(h.app->shownFit()->as<PatchDisplay>());
  CHECK(h.app->currentFit() == h.app->shownFit());
}

TEST_CASE("UI: a mesh dropped in hole-fill mode is the mesh to fill; each hole's method and result are shown") {
  Scene s;
  s.mode = SceneMode::HoleFill;
  s.holefill.preset = "sphere";
  s.sourceName = "test-holefill";
  Harness h(s, true, 900, 650);
  h.frames(2);
  REQUIRE(h.app->shownFit());
  REQUIRE(h.app->shownFit()->as<HoleFillStages>());
  // A sphere with one hole, written as PLY (which also reads as a point file outside this mode).
  TriMesh holed = hermite::testing::cutBall(hermite::holeFillPresetMesh("sphere"), Vec<3>(0, 0, -1), 0.3);
  holed.normals.resize(3, 0);
  const std::string path = (std::filesystem::temp_directory_path() / "hermite_gui_drop_holed.ply").string();
  saveMesh(path, holed);
  h.input.droppedFiles = {path};
  h.frames(3);
  CHECK(h.app->document().scene().mode == SceneMode::HoleFill);
  CHECK(h.app->document().scene().holefill.mesh == path);
  REQUIRE(h.app->shownFit());
  REQUIRE(h.app->shownFit()->as<HoleFillStages>());
  const HoleFillStages& st = *h.app->shownFit()->as<HoleFillStages>();
  CHECK(st.input.triangleCount() == holed.triangleCount());
  CHECK(st.holes.size() >= 1);
  for (const auto& hole : st.holes) {
    CHECK(hole.filled);
    CHECK((hole.method == "front" || hole.method == "min-weight"));
  }
  h.key(GLFW_KEY_Z, true);
  CHECK(h.app->document().scene().holefill.mesh.empty());
}

TEST_CASE("UI: a point file dropped on the window opens as the default scene around it, described at once") {
  Scene s;
  s.data.preset = "sphere6";
  s.sourceName = "test-drop-points";
  Harness h(s, true, 900, 650);
  h.frames(2);
  // 300 points of a sphere, positions only: normals estimated on opening.
  std::string text;
  for (int i = 0; i < 300; ++i) {
    const double z = 1 - (2 * i + 1) / 300.0, r = std::sqrt(1 - z * z), a = i * 2.399963229728653;
    text += std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a)) + " " + std::to_string(z) + "\n";
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "hermite_gui_drop_points";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "cloud.xyz").string();
  std::ofstream(path) << text;
  h.input.droppedFiles = {path};
  h.frames(3);
  const Scene& opened = h.app->document().scene();
  CHECK(opened.mode == SceneMode::Implicit3d);
  CHECK(opened.data.file == path);
  CHECK(opened.fit.kernel == KernelType::Cubic);
  CHECK(opened.fit.partition.enabled == PartitionSwitch::Auto);
  CHECK(h.app->document().path().empty());  // the data file is not the scene's file
  CHECK(documentTitle(h.app->document()) == "Hermite Lab — cloud.xyz");
  CHECK(h.app->status().message.find("loaded " + path + ": 300 samples (3D)") != std::string::npos);
  REQUIRE(h.app->currentFit());
  CHECK(h.app->currentFit()->scene.data == opened.data);
  // The fit's warnings (normals estimated) are in the message log once each, frames later too.
  h.frames(2);
  CHECK(!h.app->currentFit()->warnings().empty());
  for (const std::string& w : h.app->currentFit()->warnings()) {
    int logged = 0;
    for (const LogEntry& e : h.app->status().log) logged += e.severity == Severity::Warning && e.text == w ? 1 : 0;
    CHECK(logged == 1);
  }
  // Saving writes the scene with data.file relative to the scene's folder.
  std::filesystem::create_directories(dir / "saved");
  h.app->document().save((dir / "saved" / "cloud.json").string());
  const Scene back = loadSceneFile((dir / "saved" / "cloud.json").string());
  CHECK(back.data.file == "../cloud.xyz");
  // An unknown extension is refused with the accepted ones, the document unchanged.
  h.input.droppedFiles = {(dir / "notes.txt").string()};
  h.frames(1);
  CHECK(h.app->status().message.find("unknown file type '.txt'") != std::string::npos);
  CHECK(h.app->document().scene().data.file == path);
}

TEST_CASE("UI: an open scan fitted globally ends at its data reach; the Fit panel's switch shows the whole zero set") {
  const hermite::testing::TempDir dir;
  std::string text;
  const HermiteSamples<3> sphere = hermite::testing::goldenSphere(400);
  for (int i = 0; i < sphere.size(); ++i)  // a cap of 100 samples: a file, a global fit
    if (sphere.points(2, i) >= 0.5)
      for (int k = 0; k < 6; ++k)
        text += std::to_string(k < 3 ? sphere.points(k, i) : sphere.normals(k - 3, i)) + (k < 5 ? " " : "\n");
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.file = s.data.resolvedFile = dir.write("cap.xyzn", text);
  Harness h(s, true, 1000, 700);
  h.frames(2);
  REQUIRE(h.app->shownFit());
  const auto shownField = [&]() -> const ImplicitField<3>& { return h.app->shownFit()->as<SceneFit<3>>()->field(); };
  REQUIRE(h.app->shownFit()->as<SceneFit<3>>()->pu() == nullptr);
  CHECK_FALSE(shownField().everywhereValid());
  CHECK_FALSE(shownField().valid(Vec<3>(0, 0, -1)));
  CHECK(h.app->widgetRect("fit.reach_mask"));
  Scene whole = h.app->document().scene();
  whole.fit.reachMask = AutoSwitch::Off;
  h.app->document().apply(whole, "reach mask off");
  h.frames(3);
  REQUIRE(h.app->shownFit());
  CHECK(shownField().everywhereValid());
}
