// Nothing slow on the UI thread (issue 18): without synchronous fits the window's 3D view is
// baked and refined on the view worker. Frames return while it runs, a coarse image comes first,
// and the settled image that arrives is byte for byte the one the synchronous path draws.

#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "app/gui/gui_app.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"

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

struct App {
  std::unique_ptr<render::RenderContext> context;
  std::unique_ptr<render::OffscreenTarget> target;
  std::unique_ptr<GuiApp> app;
  FrameInput input;

  App(bool synchronous, int w, int h) {
    render::ContextOptions co;
    co.width = w;
    co.height = h;
    co.visible = false;
    context = render::createContext("osmesa", co);
    target = std::make_unique<render::OffscreenTarget>(w, h, false);
    GuiOptions o;
    o.synchronousFits = synchronous;
    app = std::make_unique<GuiApp>(Document(sphereScene()), o);
    input.width = w;
    input.height = h;
  }
  void frame() {
    target->bind();
    app->frame(input);
  }
};

}  // namespace

TEST_CASE("UI: the settled 3D view arrives from the view worker, coarse first, equal to the synchronous one") {
  SceneViewResult want;
  {
    App sync(true, 640, 480);
    for (int k = 0; k < 6; ++k) sync.frame();
    REQUIRE(sync.app->viewIsCurrent());
    want = sync.app->viewResult();
  }
  REQUIRE(want.traceMode == "baked + refined");

  App a(false, 640, 480);
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
