#pragma once
// The scripted headless UI of the app tests: the application on an OSMesa context, driven frame
// by frame with FrameInput (mouse position, buttons, keys), as a user would drive the window.

#include <filesystem>
#include <memory>

#include "app/gui/gui_app.h"
#include "app/gui/input_queue.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"

namespace hermite::app::testing {

struct Harness {
  std::unique_ptr<render::RenderContext> context;
  std::unique_ptr<render::OffscreenTarget> target;
  std::unique_ptr<GuiApp> app;
  FrameInput input;

  Harness(const Scene& scene, bool synchronous = true, int w = 1000, int h = 700, GuiOptions o = {}) {
    render::ContextOptions co;
    co.width = w;
    co.height = h;
    co.visible = false;
    context = render::createContext("osmesa", co);
    target = std::make_unique<render::OffscreenTarget>(w, h, false);
    o.synchronousFits = synchronous;
    o.screenshotDirectory = std::filesystem::temp_directory_path().string();
    app = std::make_unique<GuiApp>(Document(scene), o);
    input.width = w;
    input.height = h;
  }
  void frame() {
    target->bind();
    app->frame(input);
    input.wheel = 0;
    input.characters.clear();
    input.droppedFiles.clear();
  }
  void frames(int n) {
    for (int k = 0; k < n; ++k) frame();
  }
  void moveTo(double x, double y) {
    input.mouseX = x;
    input.mouseY = y;
    frame();
  }
  // Press at (x0, y0), move in `steps` to (x1, y1), release: a drag as ImGui and the tools see it.
  void drag(double x0, double y0, double x1, double y1, int steps = 6) {
    moveTo(x0, y0);
    input.mouseDown[0] = true;
    frame();
    for (int k = 1; k <= steps; ++k) moveTo(x0 + (x1 - x0) * k / steps, y0 + (y1 - y0) * k / steps);
    input.mouseDown[0] = false;
    frame();
  }
  void click(double x, double y) { drag(x, y, x, y, 0); }
  // Frames until the events recorded in `queue` are all taken (as the window's loop does).
  void replay(InputQueue& queue) {
    while (queue.pending() > 0) {
      input = queue.takeFrame(input.width, input.height);
      frame();
    }
  }
  void key(int code, bool ctrl = false, bool shift = false) {
    input.ctrl = ctrl;
    input.shift = shift;
    input.keysDown[code] = true;
    frame();
    input.keysDown[code] = false;
    input.ctrl = input.shift = false;
    frame();
  }
};

}  // namespace hermite::app::testing
