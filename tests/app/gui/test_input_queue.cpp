// Input as events: frames take recorded events in order, one mouse-button transition per frame
// at the position where it happened, and a key pressed and released within one frame is seen
// down for a frame.

#include <doctest/doctest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/gui/input_queue.h"

using namespace hermite::app;

namespace {

InputEvent move(double t, double x, double y) {
  InputEvent e;
  e.time = t;
  e.x = x;
  e.y = y;
  return e;
}

InputEvent button(double t, int b, bool down) {
  InputEvent e;
  e.kind = InputEvent::Kind::Button;
  e.time = t;
  e.code = b;
  e.down = down;
  return e;
}

InputEvent key(double t, int code, bool down, bool ctrl = false) {
  InputEvent e = button(t, code, down);
  e.kind = InputEvent::Kind::Key;
  e.ctrl = ctrl;
  return e;
}

}  // namespace

TEST_CASE("input queue: a click during a slow frame is replayed where it happened, press then release") {
  InputQueue q;
  // All within one 2-second frame: to the checkbox, click, then away.
  q.push(move(0.1, 50, 60));
  q.push(button(0.2, 0, true));
  q.push(button(0.3, 0, false));
  q.push(move(1.9, 700, 500));
  const FrameInput f1 = q.takeFrame(800, 600);
  CHECK(f1.mouseDown[0]);
  CHECK(f1.mouseX == 50);
  CHECK(f1.mouseY == 60);
  const FrameInput f2 = q.takeFrame(800, 600);
  CHECK(!f2.mouseDown[0]);
  CHECK(f2.mouseX == 50);  // released where it was pressed
  const FrameInput f3 = q.takeFrame(800, 600);
  CHECK(f3.mouseX == 700);
  CHECK(f3.mouseY == 500);
  CHECK(q.pending() == 0);
  CHECK(f3.width == 800);
}

TEST_CASE("input queue: moves and wheel notches between transitions share a frame; keys keep their order") {
  InputQueue q;
  q.push(move(0, 10, 10));
  q.push(move(0.01, 20, 10));
  InputEvent w;
  w.kind = InputEvent::Kind::Wheel;
  w.wheel = 1;
  q.push(w);
  q.push(w);
  const FrameInput f1 = q.takeFrame(100, 100);
  CHECK(f1.mouseX == 20);
  CHECK(f1.wheel == 2.0f);
  CHECK(q.pending() == 0);
  // Ctrl+S pressed and released before the next frame: S is seen down with Ctrl, then up.
  q.push(key(0.1, GLFW_KEY_LEFT_CONTROL, true, true));
  q.push(key(0.11, GLFW_KEY_S, true, true));
  q.push(key(0.12, GLFW_KEY_S, false, true));
  q.push(key(0.13, GLFW_KEY_LEFT_CONTROL, false, false));
  const FrameInput f2 = q.takeFrame(100, 100);
  CHECK(f2.keysDown[GLFW_KEY_S]);
  CHECK(f2.ctrl);
  CHECK(f2.wheel == 0.0f);  // a notch counts in one frame only
  const FrameInput f3 = q.takeFrame(100, 100);
  CHECK(!f3.keysDown[GLFW_KEY_S]);
  CHECK(!f3.ctrl);
  CHECK(q.pending() == 0);
}

TEST_CASE("input queue: a drag's last step and its release in one frame: the step is seen with the button held") {
  InputQueue q;
  q.push(move(0, 10, 10));
  q.push(button(0.01, 0, true));
  CHECK(q.takeFrame(100, 100).mouseDown[0]);
  // The last steps of a drag and the release arrive before the next frame.
  q.push(move(0.02, 20, 12));
  q.push(move(0.03, 30, 14));
  q.push(button(0.04, 0, false));
  const FrameInput f1 = q.takeFrame(100, 100);
  CHECK(f1.mouseDown[0]);
  CHECK(f1.mouseX == 30);
  CHECK(f1.mouseY == 14);
  const FrameInput f2 = q.takeFrame(100, 100);
  CHECK(!f2.mouseDown[0]);
  CHECK(f2.mouseX == 30);  // released where the drag ended
  CHECK(q.pending() == 0);
}

TEST_CASE("input queue: Ctrl released before the key it modifies (xdotool's ctrl+q) still reaches the key with Ctrl") {
  InputQueue q;
  q.push(key(0.10, GLFW_KEY_LEFT_CONTROL, true, false));  // a modifier's own event has the state before it
  q.push(key(0.11, GLFW_KEY_Q, true, true));
  q.push(key(0.11, GLFW_KEY_LEFT_CONTROL, false, true));
  q.push(key(0.12, GLFW_KEY_Q, false, false));
  const FrameInput f1 = q.takeFrame(100, 100);
  CHECK(f1.keysDown[GLFW_KEY_Q]);
  CHECK(f1.ctrl);
  const FrameInput f2 = q.takeFrame(100, 100);
  CHECK(!f2.ctrl);
  CHECK(!f2.keysDown[GLFW_KEY_LEFT_CONTROL]);
  const FrameInput f3 = q.takeFrame(100, 100);
  CHECK(!f3.keysDown[GLFW_KEY_Q]);
  CHECK(q.pending() == 0);
  // Ctrl pressed in an earlier frame: the same.
  q.push(key(1.0, GLFW_KEY_LEFT_CONTROL, true, false));
  CHECK(q.takeFrame(100, 100).ctrl);
  q.push(key(1.1, GLFW_KEY_S, true, true));
  q.push(key(1.1, GLFW_KEY_LEFT_CONTROL, false, true));
  q.push(key(1.2, GLFW_KEY_S, false, false));
  const FrameInput g1 = q.takeFrame(100, 100);
  CHECK(g1.keysDown[GLFW_KEY_S]);
  CHECK(g1.ctrl);
}
