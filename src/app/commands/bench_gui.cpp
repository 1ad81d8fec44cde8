#include "app/commands/bench_gui.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "app/gui/gui_app.h"
#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"

namespace hermite::app {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

DragLatencyResult benchDragLatency(int dimension, int samples, int moves, int width, int height) {
  Scene scene;
  scene.mode = dimension == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d;
  scene.data.preset = dimension == 2 ? "curve2d" : "bunny";
  scene.data.count = samples;
  const auto context = offscreenContext("osmesa", width, height);
  render::OffscreenTarget target(width, height, false);
  GuiApp app(Document(scene), GuiOptions{});
  FrameInput in;
  in.width = width;
  in.height = height;
  // As the window does: draw, present (offscreen: glFinish, so frames do not queue up in the GL
  // pipeline) and keep to 60 frames per second (the window's vsync), leaving the cores to the fit.
  auto lastFrame = std::chrono::steady_clock::now() - std::chrono::milliseconds(17);
  const auto waitForFrameSlot = [&] {
    std::this_thread::sleep_until(lastFrame + std::chrono::microseconds(16667));
    lastFrame = std::chrono::steady_clock::now();
  };
  const auto drawFrame = [&] {
    target.bind();
    app.frame(in);
    context->present();
  };
  const auto frame = [&] {
    waitForFrameSlot();
    drawFrame();
  };
  const auto settled = [&] { return app.viewIsCurrent() && !app.worker().busy(); };
  for (int k = 0; k < 2000 && !settled(); ++k) {
    frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (!settled()) throw EnvironmentError("bench: the first fit never arrived: " + app.status().message);

  // Grab a sample and move it a few pixels per step, like a slow drag.
  const int i = samples / 3;
  const auto p = app.sampleScreenPosition(i);
  if (!p) throw EnvironmentError("bench: sample not visible");
  const Vec<2> start = *p + app.viewOrigin();
  in.mouseX = start.x();
  in.mouseY = start.y();
  frame();
  in.mouseDown[0] = true;  // a click selects it, then a press on the selection grabs it
  frame();
  in.mouseDown[0] = false;
  frame();
  in.mouseDown[0] = true;
  frame();
  std::vector<double> latency, withWait, frames, fit, view;
  for (int m = 1; m <= moves; ++m) {
    // The mouse moves just after a frame began (the worst phase): the move waits for the next
    // frame slot, and that frame is the first to read it.
    const auto moved = std::chrono::steady_clock::now();
    in.mouseX = start.x() + 2.0 * m;
    in.mouseY = start.y() - 1.0 * m;
    waitForFrameSlot();
    const auto t0 = std::chrono::steady_clock::now();
    drawFrame();
    int count = 1;
    for (; count < 100000 && !app.viewIsCurrent(); ++count) frame();
    latency.push_back(msSince(t0));
    withWait.push_back(msSince(moved));
    frames.push_back(count);
    fit.push_back(app.shownFit()->implicitFit()->report.fitMs);
    view.push_back(app.viewResult().ms);
  }
  in.mouseDown[0] = false;
  frame();

  DragLatencyResult r;
  r.medianMs = median(latency);
  r.maxMs = *std::max_element(latency.begin(), latency.end());
  r.withFrameWaitMs = median(withWait);
  r.frames = median(frames);
  r.fitMs = median(fit);
  r.viewMs = median(view);
  r.samples = samples;
  r.width = width;
  r.height = height;
  r.moves = moves;
  return r;
}

}  // namespace hermite::app
