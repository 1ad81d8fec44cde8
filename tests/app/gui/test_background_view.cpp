// Nothing slow on the UI thread (issue 18): without synchronous fits the window's 3D view is
// baked and refined on the view worker. Frames return while it runs, a coarse image comes first,
// and the settled image that arrives is byte for byte the one the synchronous path draws.

#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "support/gui_harness.h"

using namespace hermite;
using namespace hermite::app;

namespace {

Scene sphereScene() {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = 40;
  s.view.showBounds = true;  // overlays are drawn over the refined pixels too
  return s;
}

}  // namespace

TEST_CASE("UI: the settled 3D view arrives from the view worker, coarse first, equal to the synchronous one") {
  SceneViewResult want;
  {
    testing::Harness sync(sphereScene(), true, 640, 480);
    for (int k = 0; k < 6; ++k) sync.frame();
    REQUIRE(sync.app->viewIsCurrent());
    want = sync.app->viewResult();
  }
  REQUIRE(want.traceMode == "baked + refined");

  testing::Harness a(sphereScene(), false, 640, 480);
  bool sawUnrefined = false, sawPending = false;
  int frames = 0;
  for (; frames < 5000 && !a.app->viewIsCurrent(); ++frames) {
    a.frame();
    sawPending = sawPending || a.app->viewPending();
    sawUnrefined = sawUnrefined || (!a.app->viewResult().image.pixels.empty() && a.app->viewResult().traceMode == "baked");
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  REQUIRE(a.app->viewIsCurrent());
  CHECK(sawPending);     // frames ran while the worker baked and refined
  CHECK(sawUnrefined);   // the baked image was on screen before the refined one
  CHECK(!a.app->viewPending());
  const SceneViewResult& got = a.app->viewResult();
  CHECK(got.traceMode == "baked + refined");
  REQUIRE(got.image.width == want.image.width);
  REQUIRE(got.image.height == want.image.height);
  CHECK(got.image.pixels == want.image.pixels);
  CHECK(got.depth == want.depth);
  CHECK(got.refinedPixels == want.refinedPixels);
}

// A drag's refit is on screen in the frame that adopts it (issue 18: drag latency of a frame or
// two): the GUI thread bakes a small model coarsely itself (in_frame_bake.h) while the view
// worker's finer bake is still on its way, which then replaces it.
TEST_CASE("UI: a drag's refit shows in the frame it arrives in, coarse, and the finer bake follows") {
  Scene s = sphereScene();
  s.data.preset = "bunny";
  testing::Harness a(s, false, 640, 480);
  for (int k = 0; k < 5000 && !(a.app->viewIsCurrent() && !a.app->worker().busy()); ++k) {
    a.frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  REQUIRE(a.app->viewIsCurrent());
  const int i = 13;
  const Vec<2> at = *a.app->sampleScreenPosition(i) + a.app->viewOrigin();
  a.moveTo(at.x(), at.y());
  a.input.ctrl = a.input.shift = true;  // Ctrl+Shift grabs any sample
  a.input.mouseDown[0] = true;
  a.frame();
  REQUIRE(a.app->selectedSample() == i);
  int adopted = 0, shownWithFit = 0, coarse = 0;
  for (int m = 1; m <= 4; ++m) {
    const std::uint64_t lastShown = a.app->shownVersion();
    a.moveTo(at.x() + 3 * m, at.y() - 2 * m);
    // Frames until the refit of this move is adopted (the fit worker takes a few ms).
    for (int k = 0; k < 2000 && a.app->shownVersion() != a.app->document().version(); ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      a.frame();
    }
    REQUIRE(a.app->shownVersion() == a.app->document().version());
    CHECK(a.app->shownVersion() != lastShown);
    ++adopted;
    // In that same frame the view was drawn from the refit, at a coarse bake (finer one pending).
    if (a.app->viewShowsCurrentFit()) ++shownWithFit;
    if (a.app->viewShowsCurrentFit() && a.app->viewPending()) ++coarse;
  }
  CHECK(shownWithFit == adopted);
  CHECK(coarse >= 1);
  // Held still, the worker's 64³ bake of the last refit arrives and the view is current.
  for (int k = 0; k < 5000 && !a.app->viewIsCurrent(); ++k) {
    a.frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  CHECK(a.app->viewIsCurrent());
  a.input.mouseDown[0] = false;
  a.input.ctrl = a.input.shift = false;
  a.frame();
}
