#include "app/gui/input_queue.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes only

#include <vector>

namespace hermite::app {

namespace {

bool isModifierKey(int key) {
  return key == GLFW_KEY_LEFT_CONTROL || key == GLFW_KEY_RIGHT_CONTROL || key == GLFW_KEY_LEFT_SHIFT ||
         key == GLFW_KEY_RIGHT_SHIFT || key == GLFW_KEY_LEFT_ALT || key == GLFW_KEY_RIGHT_ALT;
}

// The modifier keys report their own state in the next event's mods: track them directly.
void applyModifierKey(FrameInput& s, int key, bool down) {
  if (key == GLFW_KEY_LEFT_CONTROL || key == GLFW_KEY_RIGHT_CONTROL) s.ctrl = down;
  if (key == GLFW_KEY_LEFT_SHIFT || key == GLFW_KEY_RIGHT_SHIFT) s.shift = down;
  if (key == GLFW_KEY_LEFT_ALT || key == GLFW_KEY_RIGHT_ALT) s.alt = down;
}

}  // namespace

FrameInput InputQueue::takeFrame(int width, int height) {
  FrameInput& s = state_;
  s.width = width;
  s.height = height;
  s.wheel = 0;
  s.characters.clear();
  s.droppedFiles.clear();
  oldestTaken_ = events_.empty() ? -1.0 : events_.front().time;
  std::vector<int> keysChanged;
  bool movedWhileDown = false;  // the mouse moved in this frame with a button held
  bool keyWentDown = false;     // a key other than a modifier went down in this frame
  while (!events_.empty()) {
    const InputEvent& e = events_.front();
    // A button transition after a drag step in this frame waits for the next frame: this frame
    // shows the step with the button still held (a drag's last step before its release), the
    // next one the transition where it happened.
    if (movedWhileDown && e.kind == InputEvent::Kind::Button && e.code >= 0 && e.code < 3 &&
        s.mouseDown[std::size_t(e.code)] != e.down)
      break;
    if (e.kind == InputEvent::Kind::Key && e.code >= 0 && e.code < 512) {
      const bool changes = s.keysDown[std::size_t(e.code)] != e.down;
      bool seen = false;
      for (int k : keysChanged) seen = seen || k == e.code;
      if (seen && changes) break;  // its second transition: next frame
      // A modifier that changes after a key went down in this frame (xdotool's ctrl+q releases
      // Ctrl before Q) waits for the next frame: the key is seen with the modifiers it had.
      if (changes && isModifierKey(e.code) && keyWentDown) break;
    }
    switch (e.kind) {
      case InputEvent::Kind::Move:
        movedWhileDown = movedWhileDown || ((e.x != s.mouseX || e.y != s.mouseY) &&
                                            (s.mouseDown[0] || s.mouseDown[1] || s.mouseDown[2]));
        s.mouseX = e.x, s.mouseY = e.y;
        break;
      case InputEvent::Kind::Leave: s.mouseX = s.mouseY = -1; break;
      case InputEvent::Kind::Wheel: s.wheel += e.wheel; break;
      case InputEvent::Kind::Char: s.characters.push_back(unsigned(e.code)); break;
      case InputEvent::Kind::Drop: s.droppedFiles.push_back(e.path); break;
      case InputEvent::Kind::Button:
      case InputEvent::Kind::Key: {
        s.ctrl = e.ctrl, s.shift = e.shift, s.alt = e.alt;
        if (e.kind == InputEvent::Kind::Key) applyModifierKey(s, e.code, e.down);
        const bool button = e.kind == InputEvent::Kind::Button;
        if (button && e.code >= 0 && e.code < 3) {
          const bool changed = s.mouseDown[std::size_t(e.code)] != e.down;
          s.mouseDown[std::size_t(e.code)] = e.down;
          if (changed) {
            events_.pop_front();
            return s;  // one button transition per frame, at the position it happened
          }
        } else if (!button && e.code >= 0 && e.code < 512) {
          if (s.keysDown[std::size_t(e.code)] != e.down) keysChanged.push_back(e.code);
          keyWentDown = keyWentDown || (e.down && !isModifierKey(e.code));
          s.keysDown[std::size_t(e.code)] = e.down;
        }
        break;
      }
    }
    events_.pop_front();
  }
  return s;
}

}  // namespace hermite::app
