// `hermite-lab [SCENE]`: the GUI in a GLFW window. GLFW callbacks record events in an
// InputQueue that frames take in order as FrameInputs (the same struct the UI tests script);
// GuiApp draws them. Without a display the program says so on stderr and prints the scene's fit
// report instead (what earlier versions did), so a script or an ssh session still gets
// something useful.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include "app/commands/commands.h"
#include "app/gui/camera_framing.h"
#include "app/gui/frame_log.h"
#include "app/gui/frame_pacing.h"
#include "app/gui/gui_app.h"
#include "app/gui/input_queue.h"
#include "app/gui/scene_loading.h"
#include "core/base/errors.h"
#include "render/gl/context.h"

namespace hermite::app {

namespace {

// Input gathered by the callbacks: every event with its own position and time, taken by the
// frames in order (input_queue.h).
struct InputCollector {
  InputQueue queue;
  double scaleX = 1, scaleY = 1;  // framebuffer pixels per window unit (high-DPI screens)
  bool refresh = true;  // the window was resized or uncovered: its contents need a frame

  void push(InputEvent e) {
    e.time = glfwGetTime();
    queue.push(std::move(e));
  }
};

InputCollector& collector(GLFWwindow* w) { return *static_cast<InputCollector*>(glfwGetWindowUserPointer(w)); }

InputEvent modifiedEvent(InputEvent::Kind kind, int code, bool down, int mods) {
  InputEvent e;
  e.kind = kind;
  e.code = code;
  e.down = down;
  e.ctrl = mods & GLFW_MOD_CONTROL;
  e.shift = mods & GLFW_MOD_SHIFT;
  e.alt = mods & GLFW_MOD_ALT;
  return e;
}

void installCallbacks(GLFWwindow* window, InputCollector* state) {
  glfwSetWindowUserPointer(window, state);
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    InputCollector& c = collector(w);
    InputEvent e;
    e.x = x * c.scaleX;
    e.y = y * c.scaleY;
    c.push(std::move(e));
  });
  glfwSetCursorEnterCallback(window, [](GLFWwindow* w, int entered) {
    if (entered) return;
    InputEvent e;
    e.kind = InputEvent::Kind::Leave;
    collector(w).push(std::move(e));
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
    collector(w).push(modifiedEvent(InputEvent::Kind::Button, button, action == GLFW_PRESS, mods));
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    InputEvent e;
    e.kind = InputEvent::Kind::Wheel;
    e.wheel = float(dy);
    collector(w).push(std::move(e));
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    if (action == GLFW_REPEAT) return;
    collector(w).push(modifiedEvent(InputEvent::Kind::Key, key, action == GLFW_PRESS, mods));
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned codepoint) {
    InputEvent e;
    e.kind = InputEvent::Kind::Char;
    e.code = int(codepoint);
    collector(w).push(std::move(e));
  });
  glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) { collector(w).refresh = true; });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { collector(w).refresh = true; });
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    for (int i = 0; i < count; ++i) {
      InputEvent e;
      e.kind = InputEvent::Kind::Drop;
      e.path = paths[i];
      collector(w).push(std::move(e));
    }
  });
}

// A key other than a modifier is held: ImGui repeats it (the Fit panel's arrow keys step r), so
// frames go on without new events.
bool keyHeld(const FrameInput& in) {
  for (int k = 0; k < int(in.keysDown.size()); ++k)
    if (in.keysDown[std::size_t(k)] && (k < GLFW_KEY_LEFT_SHIFT || k > GLFW_KEY_RIGHT_SUPER)) return true;
  return false;
}

// The frame log's record of a frame (frame_log.h): what went down since the previous one.
FrameLog::Frame logFrame(GuiApp& app, const FrameInput& in, const FrameInput& previous, double start,
                         double oldestEvent) {
  FrameLog::Frame f;
  f.time = start;
  f.ms = 1000 * (glfwGetTime() - start);
  f.inputWaitMs = oldestEvent >= 0 ? 1000 * (start - oldestEvent) : 0;
  for (int k = 0; k < int(in.keysDown.size()); ++k)
    if (in.keysDown[std::size_t(k)] && !previous.keysDown[std::size_t(k)]) f.keysPressed.push_back(k);
  for (int b = 0; b < 3; ++b)
    if (in.mouseDown[std::size_t(b)] && !previous.mouseDown[std::size_t(b)]) f.buttonsPressed.push_back(b);
  f.fits = app.fitSubmissions();
  f.version = app.document().version();
  return f;
}

}  // namespace

int runDefault(const SceneArgs& args, double uiScale) {
  const Scene scene = framedOnLoad(loadCommandScene(args));
  // A data file is not the document's file: Save writes a scene beside it (gui_context.cpp).
  const std::string documentPath = args.scenePath.empty() || !isSceneFilePath(args.scenePath) ? "" : args.scenePath;
  std::unique_ptr<render::RenderContext> context;
  try {
    render::ContextOptions co;
    co.width = 1280;
    co.height = 800;
    co.title = documentTitle(Document(scene, documentPath));
    context = render::createContext("glfw", co);
  } catch (const EnvironmentError& e) {
    std::fprintf(stderr, "note: the GUI needs a display (%s); printing the scene's fit report instead.\n", e.what());
    FitArgs f;
    f.scene = args;
    return runFit(f);
  }
  GLFWwindow* window = context->window();
  InputCollector input;
  installCallbacks(window, &input);

  GuiOptions options;
  options.iniFile = false;  // the layout is fixed; nothing worth remembering
  options.lowPriorityFits = true;
  // The monitor's content scale (2 on a HiDPI screen) unless --ui-scale says otherwise.
  float contentScaleX = 1, contentScaleY = 1;
  glfwGetWindowContentScale(window, &contentScaleX, &contentScaleY);
  options.uiScale = uiScale > 0 ? float(uiScale) : contentScaleX;
  GuiApp app(Document(scene, documentPath), options);
  std::unique_ptr<FrameLog> log;
  if (const char* logPath = std::getenv("HERMITE_GUI_LOG"); logPath && *logPath) log = std::make_unique<FrameLog>(logPath);
  // A test hook (docs/cli.md): every frame takes at least this long, so that input arrives
  // during slow frames (tests/window/xvfb_click.sh).
  const char* delay = std::getenv("HERMITE_GUI_FRAME_DELAY_MS");
  const double frameDelayMs = delay && *delay ? std::max(0.0, std::atof(delay)) : 0.0;
  FrameInput previous;
  double last = glfwGetTime();
  std::string title = documentTitle(app.document());
  FramePacing pacing;
  while (!glfwWindowShouldClose(window) && !app.quitRequested()) {
    // Wait for events (at most 1/60 s while anything runs), and not at all while events recorded
    // earlier still wait for their frames; then draw only a frame that shows something new.
    const bool busy = app.busy(), held = keyHeld(previous);
    if (input.queue.pending() > 0) glfwPollEvents();
    else glfwWaitEventsTimeout(pacing.waitSeconds(busy || held));
    const bool hasInput = input.queue.pending() > 0 || input.refresh;
    if (!pacing.due(glfwGetTime(), hasInput, app.wantsFrame() || held, busy)) continue;
    int ww = 0, wh = 0;
    glfwGetWindowSize(window, &ww, &wh);
    const render::FramebufferSize fb = context->framebufferSize();
    if (fb.width <= 0 || fb.height <= 0) continue;  // minimised
    input.scaleX = ww > 0 ? double(fb.width) / ww : 1.0;
    input.scaleY = wh > 0 ? double(fb.height) / wh : 1.0;
    FrameInput in = input.queue.takeFrame(fb.width, fb.height);
    const double now = glfwGetTime();
    in.deltaSeconds = now - last;
    last = now;
    app.frame(in);
    pacing.drawn(now, hasInput);
    input.refresh = false;
    if (frameDelayMs > 0) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(frameDelayMs));
    context->present();
    if (log) {
      FrameLog::Frame f = logFrame(app, in, previous, now, input.queue.oldestTakenTime());
      f.fitRunning = app.worker().busy();
      f.viewPending = app.viewPending();
      f.phases = app.lastPhases();
      f.selected = app.selectedSample();
      log->frame(f);
      log->widgets(app.widgetRects());
    }
    previous = std::move(in);
    if (std::string shown = documentTitle(app.document()); shown != title) {
      title = std::move(shown);
      glfwSetWindowTitle(window, title.c_str());
    }
  }
  return 0;
}

}  // namespace hermite::app
