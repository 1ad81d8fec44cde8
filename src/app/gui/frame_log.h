#pragma once
// The window's frame log (HERMITE_GUI_LOG=FILE, docs/cli.md): one JSON object per line and
// frame with what the Xvfb tests time and check from outside the process — the frame's duration,
// how long its oldest input event waited for it, the keys and mouse buttons that went down, the
// fits submitted so far, the document's version, whether a fit or work for the view runs, the ms of each step of the frame (frame_phases.h) — and,
// whenever the named widgets move, their rectangles (how the tests find a checkbox to click).

#include <array>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "app/gui/frame_phases.h"

namespace hermite::app {

class FrameLog {
 public:
  struct Frame {
    double time = 0;        // s, the window's clock (glfwGetTime) at the frame's start
    double ms = 0;          // the frame: GuiApp::frame and the buffer swap
    double inputWaitMs = 0; // the frame's start less the time of the oldest event it took (0: none)
    std::vector<int> keysPressed;     // GLFW key codes that went down in this frame
    std::vector<int> buttonsPressed;  // 0 left, 1 right, 2 middle
    int fits = 0;                     // fits submitted so far
    std::uint64_t version = 0;        // the document's version
    bool fitRunning = false, viewPending = false;
    int selected = -1;                // the selected sample (−1: none)
    FramePhases phases;               // GuiApp::frame's steps (without the buffer swap)
    int drawVertices = 0, drawCommands = 0;  // the frame's ImGui draw data
  };
  using Widgets = std::map<std::string, std::array<float, 4>>;

  // Appends to `path` (created). Throws EnvironmentError when it cannot be opened.
  explicit FrameLog(const std::string& path);
  ~FrameLog();
  FrameLog(const FrameLog&) = delete;
  FrameLog& operator=(const FrameLog&) = delete;

  void frame(const Frame& f);
  // Writes the rectangles (min x, min y, max x, max y in window pixels) when they changed.
  void widgets(const Widgets& rects);

 private:
  std::FILE* file_ = nullptr;
  long long frames_ = 0;
  Widgets lastWidgets_;
};

}  // namespace hermite::app
