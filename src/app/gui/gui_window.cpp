// `hermite-lab [SCENE]`: the GUI in a GLFW window. GLFW callbacks fill a FrameInput per frame
// (the same struct the UI tests script), GuiApp draws it. Without a display the program says so
// on stderr and prints the scene's fit report instead (what earlier versions did), so a script
// or an ssh session still gets something useful.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include "app/commands/commands.h"
#include "app/gui/camera_framing.h"
#include "app/gui/gui_app.h"
#include "app/gui/scene_loading.h"
#include "core/base/errors.h"
#include "render/gl/context.h"

namespace hermite::app {

namespace {

// Input gathered by the callbacks between two frames.
struct InputCollector {
  FrameInput input;
  float wheel = 0;
  std::vector<unsigned> characters;
  std::vector<std::string> dropped;
  double scaleX = 1, scaleY = 1;  // framebuffer pixels per window unit (high-DPI screens)
  // Presses since the last frame: a key or button pressed and released between two frames
  // (xdotool, fast typing) must still be seen down for one frame.
  std::array<bool, 512> keyLatch{};
  std::array<bool, 3> buttonLatch{};
  bool ctrlLatch = false, shiftLatch = false;

  // The input of the next frame, and the latches reset.
  FrameInput take() {
    FrameInput in = input;
    for (int k = 0; k < 512; ++k) in.keysDown[k] = in.keysDown[k] || keyLatch[k];
    for (int b = 0; b < 3; ++b) in.mouseDown[b] = in.mouseDown[b] || buttonLatch[b];
    in.ctrl = in.ctrl || ctrlLatch;
    in.shift = in.shift || shiftLatch;
    in.wheel = wheel;
    in.characters = std::move(characters);
    in.droppedFiles = std::move(dropped);
    keyLatch.fill(false);
    buttonLatch.fill(false);
    ctrlLatch = shiftLatch = false;
    wheel = 0;
    characters.clear();
    dropped.clear();
    return in;
  }
};

InputCollector& collector(GLFWwindow* w) { return *static_cast<InputCollector*>(glfwGetWindowUserPointer(w)); }

void installCallbacks(GLFWwindow* window, InputCollector* state) {
  glfwSetWindowUserPointer(window, state);
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    InputCollector& c = collector(w);
    c.input.mouseX = x * c.scaleX;
    c.input.mouseY = y * c.scaleY;
  });
  glfwSetCursorEnterCallback(window, [](GLFWwindow* w, int entered) {
    if (!entered) collector(w).input.mouseX = collector(w).input.mouseY = -1;
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
    InputCollector& c = collector(w);
    if (button >= 0 && button < 3) {
      c.input.mouseDown[button] = action == GLFW_PRESS;
      if (action == GLFW_PRESS) c.buttonLatch[button] = true;
    }
    c.input.ctrl = mods & GLFW_MOD_CONTROL;
    c.input.shift = mods & GLFW_MOD_SHIFT;
    c.input.alt = mods & GLFW_MOD_ALT;
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) { collector(w).wheel += float(dy); });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    InputCollector& c = collector(w);
    if (key >= 0 && key < 512 && action != GLFW_REPEAT) {
      c.input.keysDown[key] = action == GLFW_PRESS;
      if (action == GLFW_PRESS) c.keyLatch[key] = true;
    }
    c.input.ctrl = mods & GLFW_MOD_CONTROL;
    c.input.shift = mods & GLFW_MOD_SHIFT;
    c.input.alt = mods & GLFW_MOD_ALT;
    if (action == GLFW_PRESS) {
      c.ctrlLatch = c.ctrlLatch || c.input.ctrl;
      c.shiftLatch = c.shiftLatch || c.input.shift;
    }
    // Modifier keys report their own state in the next event's mods: track them directly.
    if (key == GLFW_KEY_LEFT_CONTROL || key == GLFW_KEY_RIGHT_CONTROL) c.input.ctrl = action != GLFW_RELEASE;
    if (key == GLFW_KEY_LEFT_SHIFT || key == GLFW_KEY_RIGHT_SHIFT) c.input.shift = action != GLFW_RELEASE;
    if (key == GLFW_KEY_LEFT_ALT || key == GLFW_KEY_RIGHT_ALT) c.input.alt = action != GLFW_RELEASE;
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned codepoint) { collector(w).characters.push_back(codepoint); });
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    for (int i = 0; i < count; ++i) collector(w).dropped.emplace_back(paths[i]);
  });
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
  // The monitor's content scale (2 on a HiDPI screen) unless --ui-scale says otherwise.
  float contentScaleX = 1, contentScaleY = 1;
  glfwGetWindowContentScale(window, &contentScaleX, &contentScaleY);
  options.uiScale = uiScale > 0 ? float(uiScale) : contentScaleX;
  GuiApp app(Document(scene, documentPath), options);
  double last = glfwGetTime();
  std::string title = documentTitle(app.document());
  while (!glfwWindowShouldClose(window) && !app.quitRequested()) {
    // Wait for events while nothing is moving; poll while a fit, a sweep or a redraw is pending.
    if (app.worker().busy() || app.explorer().running()) glfwWaitEventsTimeout(1.0 / 60.0);
    else glfwWaitEventsTimeout(0.1);
    int ww = 0, wh = 0;
    glfwGetWindowSize(window, &ww, &wh);
    const render::FramebufferSize fb = context->framebufferSize();
    if (fb.width <= 0 || fb.height <= 0) continue;  // minimised
    input.scaleX = ww > 0 ? double(fb.width) / ww : 1.0;
    input.scaleY = wh > 0 ? double(fb.height) / wh : 1.0;
    FrameInput in = input.take();
    in.width = fb.width;
    in.height = fb.height;
    const double now = glfwGetTime();
    in.deltaSeconds = now - last;
    last = now;
    app.frame(in);
    context->present();
    if (std::string shown = documentTitle(app.document()); shown != title) {
      title = std::move(shown);
      glfwSetWindowTitle(window, title.c_str());
    }
  }
  return 0;
}

}  // namespace hermite::app
