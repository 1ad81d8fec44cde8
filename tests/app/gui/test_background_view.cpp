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
