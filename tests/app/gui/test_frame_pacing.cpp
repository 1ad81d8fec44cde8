// The window draws only frames that show something new (frame_pacing.h): input and the frames
// after it, work waiting for the GL thread, a few frames a second while a fit or a view job runs,
// rarely when idle. A paced window still reaches the settled, refined view, with fewer frames.

#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "app/gui/frame_pacing.h"
#include "support/gui_harness.h"

using namespace hermite;
using namespace hermite::app;

TEST_CASE("frame pacing: input, its follow-up frames, waiting work, and the busy and idle intervals") {
  FramePacing p;
  CHECK(p.due(0.0, false, false, false));  // the first frame
  p.drawn(0.0, false);
  CHECK_FALSE(p.due(0.01, false, false, false));
  CHECK_FALSE(p.due(0.01, false, false, true));
  CHECK(p.due(0.01, true, false, false));  // input
  CHECK(p.due(0.01, false, true, false));  // work for the GL thread
  CHECK_FALSE(p.due(FramePacing::kBusyInterval - 0.01, false, false, true));
  CHECK(p.due(FramePacing::kBusyInterval + 0.01, false, false, true));
  CHECK_FALSE(p.due(FramePacing::kIdleInterval - 0.01, false, false, false));
  CHECK(p.due(FramePacing::kIdleInterval + 0.01, false, false, false));
  // After a frame with input, kFollowUpFrames frames follow without any.
  p.drawn(1.0, true);
  for (int k = 0; k < FramePacing::kFollowUpFrames; ++k) {
    CHECK(p.due(1.0 + 0.001 * (k + 1), false, false, false));
    CHECK(p.waitSeconds(false) < 0.02);
    p.drawn(1.0 + 0.001 * (k + 1), false);
  }
  CHECK_FALSE(p.due(1.01, false, false, false));
  CHECK(p.waitSeconds(false) == doctest::Approx(FramePacing::kIdleInterval));
  CHECK(p.waitSeconds(true) < 0.02);
}

namespace {

Scene sphereScene() {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = 40;
  return s;
}

// Ticks at ~500 Hz for at most `seconds`, drawing a frame only when `pacing` says one is due, until
// the view shows the current fit refined and nothing runs. Returns the frames drawn.
int settlePaced(testing::Harness& a, FramePacing& pacing, double seconds, int& ticks) {
  const auto t0 = std::chrono::steady_clock::now();
  int frames = 0;
  ticks = 0;
  while (!(a.app->viewIsCurrent() && !a.app->busy())) {
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (now > seconds) break;
    ++ticks;
    if (pacing.due(now, false, a.app->wantsFrame(), a.app->busy())) {
      a.frame();
      pacing.drawn(now, false);
      ++frames;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return frames;
}

}  // namespace

TEST_CASE("UI: a paced window settles with frames only when something is new, and wants none when idle") {
  testing::Harness a(sphereScene(), false, 640, 480);
  FramePacing pacing;
  int ticks = 0;
  settlePaced(a, pacing, 60, ticks);
  REQUIRE(a.app->viewIsCurrent());
  CHECK(a.app->viewResult().traceMode == "baked + refined");
  CHECK_FALSE(a.app->wantsFrame());
  CHECK_FALSE(a.app->busy());

  // A change made between frames wants a frame; the refit it starts settles again, and the
  // frames drawn are fewer than the ticks (the worker's time goes by without frames).
  Scene next = a.app->document().scene();
  next.data.count = 60;
  a.app->document().apply(next, "count");
  CHECK(a.app->wantsFrame());
  const int frames = settlePaced(a, pacing, 60, ticks);
  REQUIRE(a.app->viewIsCurrent());
  CHECK(a.app->viewResult().traceMode == "baked + refined");
  CHECK(a.app->shownFit()->scene.data.count == 60);
  CHECK(frames < ticks);
  CHECK_FALSE(a.app->wantsFrame());
}
