#include "app/commands/bench_gui.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include "app/gui/frame_log.h"
#include "app/gui/frame_pacing.h"
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

// The window's options (gui_window.cpp) that change what a frame costs.
GuiOptions windowOptions() {
  GuiOptions o;
  o.lowPriorityFits = true;
  return o;
}

// At most one frame per 1/60 s, as under the window's vsync: wait() returns at the next slot.
struct FrameSlot {
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now() - std::chrono::milliseconds(17);
  void wait() {
    std::this_thread::sleep_until(last + std::chrono::microseconds(16667));
    last = std::chrono::steady_clock::now();
  }
};

}  // namespace

namespace {

// GuiApp on an OSMesa context drawing frames as the window does: draw, present (offscreen:
// glFinish, so frames do not queue up in the GL pipeline) and keep to 60 frames per second (the
// window's vsync), leaving the cores to the fit.
struct DragBench {
  std::unique_ptr<render::RenderContext> context;
  render::OffscreenTarget target;
  GuiApp app;
  FrameInput in;
  FrameSlot slot;

  DragBench(const Scene& scene, int width, int height)
      : context(offscreenContext("osmesa", width, height)), target(width, height, false),
        app(Document(scene), windowOptions()) {
    in.width = width;
    in.height = height;
  }
  void waitForFrameSlot() { slot.wait(); }
  void drawFrame() {
    target.bind();
    app.frame(in);
    context->present();
  }
  void frame() {
    waitForFrameSlot();
    drawFrame();
  }
  bool settled() { return app.viewIsCurrent() && !app.worker().busy(); }
  // Frames until the first fit and its view are on screen.
  void settle() {
    for (int k = 0; k < 2000 && !settled(); ++k) {
      frame();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (!settled()) throw EnvironmentError("bench: the first fit never arrived: " + app.status().message);
  }
  // Presses on sample `i` twice: a click selects it, then a press on the selection grabs it.
  // Returns the window position of the press.
  Vec<2> grab(int i) {
    const auto p = app.sampleScreenPosition(i);
    if (!p) throw EnvironmentError("bench: sample not visible");
    const Vec<2> start = *p + app.viewOrigin();
    in.mouseX = start.x();
    in.mouseY = start.y();
    frame();
    in.mouseDown[0] = true;
    frame();
    in.mouseDown[0] = false;
    frame();
    in.mouseDown[0] = true;
    frame();
    return start;
  }
};

struct MoveTimes {
  double shownMs = 0, finalMs = 0, sinceMoveMs = 0;
  int frames = 0;
};

// One move of the grabbed sample to `to`, timed until the view shows the refit (at any quality)
// and until it shows it at its final quality. The mouse moves just after a frame began (the worst
// phase): the move waits for the next frame slot, and that frame is the first to read it.
MoveTimes timeMove(DragBench& b, const Vec<2>& to) {
  MoveTimes t;
  const auto moved = std::chrono::steady_clock::now();
  b.in.mouseX = to.x();
  b.in.mouseY = to.y();
  b.waitForFrameSlot();
  const auto t0 = std::chrono::steady_clock::now();
  b.drawFrame();
  int count = 1;
  for (; count < 100000 && !b.app.viewShowsCurrentFit(); ++count) b.frame();
  t.shownMs = msSince(t0);
  t.sinceMoveMs = msSince(moved);
  t.frames = count;
  for (; count < 100000 && !b.app.viewIsCurrent(); ++count) b.frame();
  t.finalMs = msSince(t0);
  return t;
}

}  // namespace

DragLatencyResult benchDragLatency(int dimension, int samples, int moves, int width, int height) {
  Scene scene;
  scene.mode = dimension == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d;
  scene.data.preset = dimension == 2 ? "curve2d" : "bunny";
  scene.data.count = samples;
  DragBench b(scene, width, height);
  b.settle();
  // Grab a sample and move it a few pixels per step, like a slow drag.
  const Vec<2> start = b.grab(samples / 3);
  std::vector<double> latency, finalLatency, withWait, frames, fit, view;
  for (int m = 1; m <= moves; ++m) {
    const MoveTimes t = timeMove(b, start + Vec<2>(2.0 * m, -1.0 * m));
    latency.push_back(t.shownMs);
    finalLatency.push_back(t.finalMs);
    withWait.push_back(t.sinceMoveMs);
    frames.push_back(t.frames);
    fit.push_back(b.app.shownFit()->implicitFit()->report.fitMs);
    view.push_back(b.app.viewResult().ms);
  }
  b.in.mouseDown[0] = false;
  b.frame();

  DragLatencyResult r;
  r.medianMs = median(latency);
  r.maxMs = *std::max_element(latency.begin(), latency.end());
  r.finalMs = median(finalLatency);
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

namespace {

// GuiApp on an OSMesa context, frames paced at 60 Hz as under vsync, each timed. As in the
// window (frame_pacing.h), a frame without input is drawn only when it would show something new.
struct PacedApp {
  std::unique_ptr<render::RenderContext> context;
  render::OffscreenTarget target;
  GuiApp app;
  FrameInput in;
  std::chrono::steady_clock::time_point lastFrame = std::chrono::steady_clock::now();
  FrameSlot slot;
  std::vector<double> frameMs;
  FramePhases worstPhases;
  double worstPresentMs = 0;
  std::unique_ptr<FrameLog> log;  // HERMITE_GUI_LOG, as in the window: every frame with its steps
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  FramePacing pacing;

  PacedApp(const Scene& scene, int width, int height)
      : context(offscreenContext("osmesa", width, height)), target(width, height, false),
        app(Document(scene), windowOptions()) {
    in.width = width;
    in.height = height;
    if (const char* path = std::getenv("HERMITE_GUI_LOG"); path && *path) log = std::make_unique<FrameLog>(path);
  }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
  // The next 60 Hz slot; a frame there when the window would draw one (no input arrives here).
  void tick() {
    slot.wait();
    if (pacing.due(seconds(), false, app.wantsFrame(), app.busy())) draw(false);
  }
  // A frame with the input in `in`, at the next 60 Hz slot.
  void frame() {
    slot.wait();
    draw(true);
  }
  void draw(bool input) {
    lastFrame = std::chrono::steady_clock::now();
    target.bind();
    app.frame(in);
    pacing.drawn(seconds(), input);
    const auto presented = std::chrono::steady_clock::now();
    context->present();
    frameMs.push_back(msSince(lastFrame));
    if (frameMs.back() >= *std::max_element(frameMs.begin(), frameMs.end())) {
      worstPhases = app.lastPhases();
      worstPresentMs = msSince(presented);
    }
    if (log) {
      FrameLog::Frame f;
      f.time = std::chrono::duration<double>(lastFrame - start).count();
      f.ms = frameMs.back();
      f.fits = app.fitSubmissions();
      f.version = app.document().version();
      f.fitRunning = app.worker().busy();
      f.viewPending = app.viewPending();
      f.selected = app.selectedSample();
      f.phases = app.lastPhases();
      f.drawVertices = app.lastDrawVertices();
      f.drawCommands = app.lastDrawCommands();
      log->frame(f);
    }
  }
  bool settled() { return app.viewIsCurrent() && !app.worker().busy(); }
  void clearTimes() {
    frameMs.clear();
    worstPhases = {};
    worstPresentMs = 0;
  }
  // Frames until settled (at most `limitSeconds`); throws when it never settles. The settled
  // quality starts a few frames after the last interaction, and its bake and refinement then
  // arrive from the view worker: the frames before it count, and so do those until it is on screen.
  void settle(double limitSeconds) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 6; ++k) tick();
    while (!settled()) {
      if (msSince(t0) > limitSeconds * 1000)
        throw EnvironmentError("bench: the view did not settle in " + std::to_string(limitSeconds) +
                               " s: " + app.status().message);
      tick();
    }
  }
  BusyFramesResult result(int samples, double totalMs) const {
    BusyFramesResult r;
    r.worstMs = frameMs.empty() ? 0 : *std::max_element(frameMs.begin(), frameMs.end());
    r.medianMs = median(frameMs);
    r.frames = int(frameMs.size());
    r.totalMs = totalMs;
    r.samples = samples;
    r.width = in.width;
    r.height = in.height;
    r.worstPhases = worstPhases;
    r.worstPresentMs = worstPresentMs;
    r.fitMs = app.shownFit() ? app.shownFit()->wallMs : 0.0;
    r.over33 = double(std::count_if(frameMs.begin(), frameMs.end(), [](double ms) { return ms > 33.0; }));
    return r;
  }
};

// Two interlinked tori: a preset that has 5 000 samples (the bunny has at most 1 839).
Scene toriScene(int samples, bool partition) {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "two-tori";
  s.data.count = samples;
  s.fit.partition.enabled = partition ? PartitionSwitch::On : PartitionSwitch::Off;
  return s;
}

}  // namespace

BusyFramesResult benchFramesDuringDenseFit(int samples, int width, int height) {
  PacedApp p(toriScene(50, false), width, height);
  p.settle(60);
  p.clearTimes();
  const auto t0 = std::chrono::steady_clock::now();
  p.app.document().apply(toriScene(samples, false), "count");
  p.settle(3600);
  return p.result(samples, msSince(t0));
}

BusyFramesResult benchFramesDuringSettledRender(int samples, int width, int height) {
  PacedApp p(toriScene(samples, true), width, height);
  p.settle(600);
  // Orbit: press in the view's lower-left corner (empty), move, release.
  const Vec<2> o = p.app.viewOrigin();
  p.in.mouseX = o.x() + 30;
  p.in.mouseY = o.y() + p.app.viewSize().y() - 40;
  p.frame();
  p.in.mouseDown[0] = true;
  p.frame();
  for (int k = 0; k < 5; ++k) {
    p.in.mouseX += 12;
    p.frame();
  }
  p.in.mouseDown[0] = false;
  p.clearTimes();
  const auto t0 = std::chrono::steady_clock::now();
  p.settle(600);
  return p.result(samples, msSince(t0));
}

}  // namespace hermite::app
