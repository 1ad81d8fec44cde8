#pragma once
// Input as events (issue 18): every mouse and key event is recorded with its own position and
// time, and frames take them in order. ImGui 1.86 reads a state per frame, not a queue, so a
// frame takes events only up to the first mouse-button transition, or up to a second transition
// of a key it already saw change: a click that arrived during a slow frame is replayed over the
// next frames at the position where it happened, and a press and release within one frame are
// still seen as a press, then a release. GLFW-free (key codes are GLFW's), so tests script it.
// The GLFW window (gui_window.cpp) and the UI tests drive GuiApp through it.

#include <cstddef>
#include <deque>
#include <string>

#include "app/gui/gui_input.h"

namespace hermite::app {

struct InputEvent {
  enum class Kind { Move, Leave, Button, Key, Wheel, Char, Drop };
  Kind kind = Kind::Move;
  double time = 0;           // seconds (the window's clock)
  double x = -1, y = -1;     // Move: framebuffer pixels
  int code = 0;              // Button: 0 left, 1 right, 2 middle; Key: GLFW key code; Char: code point
  bool down = false;         // Button / Key: pressed (true) or released
  bool ctrl = false, shift = false, alt = false;  // Button / Key: the modifiers with the event
  float wheel = 0;           // Wheel: notches, + = away from the user
  std::string path;          // Drop
};

class InputQueue {
 public:
  void push(InputEvent e) { events_.push_back(std::move(e)); }
  // Events not yet taken by a frame.
  std::size_t pending() const { return events_.size(); }
  // The next frame's input: the state after the events it takes (see above), of size
  // width × height. Events left over wait for the following frames.
  FrameInput takeFrame(int width, int height);
  // The state the taken events left (mouse, buttons, keys, modifiers).
  const FrameInput& state() const { return state_; }
  // The time of the oldest event the last takeFrame took; −1 when it took none.
  double oldestTakenTime() const { return oldestTaken_; }

 private:
  std::deque<InputEvent> events_;
  FrameInput state_;
  double oldestTaken_ = -1;
};

}  // namespace hermite::app
