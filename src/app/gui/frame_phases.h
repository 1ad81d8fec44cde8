#pragma once
// Where a GUI frame's time went: wall clock per step of GuiApp::frame, in ms. The frame log
// (HERMITE_GUI_LOG) writes them for slow frames and the GUI benches report the worst frame's, so
// a slow frame says which step it was (a wait on another thread, an upload, a trace band).

#include <array>
#include <chrono>
#include <string_view>

namespace hermite::app {

enum class FramePhase {
  Input,     // ImGui input, NewFrame, shortcuts and the view's gestures
  AdoptFit,  // taking finished fits from the fit worker (both polls)
  Panels,    // the panels' widgets (they read the shown fit)
  Submit,    // submitting a refit (a quick one is waited for here)
  View,      // the view image: adopting background work, trace bands, uploads
  Overlays,  // selection, handles, boxes, gizmo, help, status bar
  Render,    // ImGui::Render and its GL draw
  Count
};

constexpr std::array<std::string_view, std::size_t(FramePhase::Count)> kFramePhaseNames{
    "input", "adopt_fit", "panels", "submit", "view", "overlays", "render"};

struct FramePhases {
  std::array<double, std::size_t(FramePhase::Count)> ms{};  // ms per phase of one frame
  double operator[](FramePhase p) const { return ms[std::size_t(p)]; }
  double total() const {
    double t = 0;
    for (double m : ms) t += m;
    return t;
  }
};

// Adds the time since the last mark (or construction) to a phase of `phases`.
class FramePhaseTimer {
 public:
  explicit FramePhaseTimer(FramePhases& phases) : phases_(phases) { phases_ = {}; }
  void mark(FramePhase p) {
    const auto now = std::chrono::steady_clock::now();
    phases_.ms[std::size_t(p)] += std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
  }

 private:
  FramePhases& phases_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace hermite::app
