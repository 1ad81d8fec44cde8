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

// The GLFW window of the scene's document, or null (after a note on stderr) without a display.
std::unique_ptr<render::RenderContext> openWindow(const Scene& scene, const std::string& documentPath) {
  try {
    render::ContextOptions co;
    co.width = 1280;
    co.height = 800;
    co.title = documentTitle(Document(scene, documentPath));
    return render::createContext("glfw", co);
  } catch (const EnvironmentError& e) {
    std::fprintf(stderr, "note: the GUI needs a display (%s); printing the scene's fit report instead.\n", e.what());
    return nullptr;
  }
}

// The window's GUI options: the monitor's content scale (2 on a HiDPI screen) unless --ui-scale
// (uiScale > 0) says otherwise.
GuiOptions windowGuiOptions(GLFWwindow* window, double uiScale) {
  GuiOptions options;
  options.iniFile = false;  // the layout is fixed; nothing worth remembering
  options.lowPriorityFits = true;
  float contentScaleX = 1, contentScaleY = 1;
  glfwGetWindowContentScale(window, &contentScaleX, &contentScaleY);
  options.uiScale = uiScale > 0 ? float(uiScale) : contentScaleX;
  return options;
}

// The window's frame loop and what it carries from one frame to the next.
class FrameLoop {
 public:
  FrameLoop(render::RenderContext& context, InputCollector& input, GuiApp& app)
      : context_(context), window_(context.window()), input_(input), app_(app) {
    if (const char* logPath = std::getenv("HERMITE_GUI_LOG"); logPath && *logPath)
      log_ = std::make_unique<FrameLog>(logPath);
    // A test hook (docs/cli.md): every frame takes at least this long, so that input arrives
    // during slow frames (tests/window/xvfb_click.sh).
    const char* delay = std::getenv("HERMITE_GUI_FRAME_DELAY_MS");
    frameDelayMs_ = delay && *delay ? std::max(0.0, std::atof(delay)) : 0.0;
    last_ = glfwGetTime();
    title_ = documentTitle(app.document());
  }

  // Frames until the window closes or the app asks to quit.
  void run() {
    while (!glfwWindowShouldClose(window_) && !app_.quitRequested()) {
      // Wait for events (at most 1/60 s while anything runs), and not at all while events recorded
      // earlier still wait for their frames; then draw only a frame that shows something new.
      const bool busy = app_.busy(), held = keyHeld(previous_);
      if (input_.queue.pending() > 0) glfwPollEvents();
      else glfwWaitEventsTimeout(pacing_.waitSeconds(busy || held));
      const bool hasInput = input_.queue.pending() > 0 || input_.refresh;
      if (!pacing_.due(glfwGetTime(), hasInput, app_.wantsFrame() || held, busy)) continue;
      drawFrame(hasInput);
    }
  }

 private:
  // Takes the input waiting since the last frame, draws it and shows it; nothing while minimised.
  void drawFrame(bool hasInput) {
    int ww = 0, wh = 0;
    glfwGetWindowSize(window_, &ww, &wh);
    const render::FramebufferSize fb = context_.framebufferSize();
    if (fb.width <= 0 || fb.height <= 0) return;  // minimised
    input_.scaleX = ww > 0 ? double(fb.width) / ww : 1.0;
    input_.scaleY = wh > 0 ? double(fb.height) / wh : 1.0;
    FrameInput in = input_.queue.takeFrame(fb.width, fb.height);
    const double now = glfwGetTime();
    in.deltaSeconds = now - last_;
    last_ = now;
    app_.frame(in);
    pacing_.drawn(now, hasInput);
    input_.refresh = false;
    if (frameDelayMs_ > 0) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(frameDelayMs_));
    context_.present();
    if (log_) logDrawnFrame(in, now);
    previous_ = std::move(in);
    if (std::string shown = documentTitle(app_.document()); shown != title_) {
      title_ = std::move(shown);
      glfwSetWindowTitle(window_, title_.c_str());
    }
  }

  // The frame log's records of the frame drawn at `start` from input `in`.
  void logDrawnFrame(const FrameInput& in, double start) {
    FrameLog::Frame f = logFrame(app_, in, previous_, start, input_.queue.oldestTakenTime());
    f.fitRunning = app_.worker().busy();
    f.viewPending = app_.viewPending();
    f.phases = app_.lastPhases();
    f.drawVertices = app_.lastDrawVertices();
    f.drawCommands = app_.lastDrawCommands();
    f.selected = app_.selectedSample();
    log_->frame(f);
    log_->widgets(app_.widgetRects());
  }

  render::RenderContext& context_;
  GLFWwindow* window_;
  InputCollector& input_;
  GuiApp& app_;
  std::unique_ptr<FrameLog> log_;  // HERMITE_GUI_LOG's frame log, or null
  double frameDelayMs_ = 0;        // HERMITE_GUI_FRAME_DELAY_MS, ≥ 0
  FramePacing pacing_;
  FrameInput previous_;            // the last frame's input
  double last_ = 0;                // glfwGetTime() of the last frame, seconds
  std::string title_;              // the window's title
};

}  // namespace

int runDefault(const SceneArgs& args, double uiScale) {
  const Scene scene = framedOnLoad(loadCommandScene(args));
  // A data file is not the document's file: Save writes a scene beside it (gui_context.cpp).
  const std::string documentPath = args.scenePath.empty() || !isSceneFilePath(args.scenePath) ? "" : args.scenePath;
  const std::unique_ptr<render::RenderContext> context = openWindow(scene, documentPath);
  if (!context) {
    FitArgs f;
    f.scene = args;
    return runFit(f);
  }
  InputCollector input;
  installCallbacks(context->window(), &input);
  GuiApp app(Document(scene, documentPath), windowGuiOptions(context->window(), uiScale));
  FrameLoop(*context, input, app).run();
  return 0;
}

}  // namespace hermite::app
