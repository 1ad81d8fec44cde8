#pragma once
// When the window draws a frame. Every frame of the whole window costs the software rasteriser
// the same CPU whatever it shows (most while a fit holds the cores: docs/performance.md, "GUI
// frame"), so frames that would show nothing new are skipped: a frame is drawn for input (and a
// few frames after it, for ImGui's hover state), for work that waits for the GL thread (a
// finished fit, a bake to upload, trace bands, refined rows), a few times a second while a fit or
// a view job runs (progress and elapsed times), and rarely when idle. The window polls these
// conditions at 60 Hz while anything runs; a skipped frame costs nothing, and the CPU it leaves
// goes to the fit and the view's refinement.

namespace hermite::app {

class FramePacing {
 public:
  // Frames drawn after the last one that had input (ImGui settles hover and active states).
  static constexpr int kFollowUpFrames = 2;
  // Seconds between frames while a fit or view job runs with nothing new to show, and when idle.
  static constexpr double kBusyInterval = 0.2;
  static constexpr double kIdleInterval = 0.5;

  // Whether to draw a frame at `now` (s): `input` when events wait for it, `work` when the GL
  // thread has something to show or do (GuiApp::wantsFrame), `busy` while a fit or a view job runs.
  bool due(double now, bool input, bool work, bool busy) const;
  // A frame was drawn at `now`; `input` when it carried events.
  void drawn(double now, bool input);
  // How long the window may wait for events before asking due() again (s).
  double waitSeconds(bool busy) const { return busy || followUps_ > 0 ? 1.0 / 60.0 : kIdleInterval; }

 private:
  double last_ = -1e300;  // time of the last frame drawn
  int followUps_ = 0;     // frames still to draw after input
};

}  // namespace hermite::app
