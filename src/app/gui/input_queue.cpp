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

// What a frame has taken so far, for the rules that end it before an event.
struct FrameSoFar {
  std::vector<int> keysChanged;
  bool movedWhileDown = false;  // the mouse moved with a button held
  bool keyWentDown = false;     // a key other than a modifier went down

  // `e` waits for the next frame: a button transition after a drag step (this frame shows the
  // step with the button still held — a drag's last step before its release — the next one the
  // transition where it happened); a key's second transition; a modifier that changes after a
  // key went down (xdotool's ctrl+q releases Ctrl before Q: the key is seen with the modifiers
  // it had).
  bool endsBefore(const InputEvent& e, const FrameInput& s) const {
    if (e.kind == InputEvent::Kind::Button && e.code >= 0 && e.code < 3)
      return movedWhileDown && s.mouseDown[std::size_t(e.code)] != e.down;
    if (e.kind != InputEvent::Kind::Key || e.code < 0 || e.code >= 512) return false;
    if (s.keysDown[std::size_t(e.code)] == e.down) return false;
    for (int k : keysChanged)
      if (k == e.code) return true;
    return isModifierKey(e.code) && keyWentDown;
  }
};

}  // namespace

FrameInput InputQueue::takeFrame(int width, int height) {
  FrameInput& s = state_;
  s.width = width;
  s.height = height;
  s.wheel = 0;
  s.characters.clear();
  s.droppedFiles.clear();
  oldestTaken_ = events_.empty() ? -1.0 : events_.front().time;
  FrameSoFar taken;
  for (; !events_.empty(); events_.pop_front()) {
    const InputEvent& e = events_.front();
    if (taken.endsBefore(e, s)) break;
    switch (e.kind) {
      case InputEvent::Kind::Move:
        taken.movedWhileDown = taken.movedWhileDown || ((e.x != s.mouseX || e.y != s.mouseY) &&
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
          if (s.keysDown[std::size_t(e.code)] != e.down) taken.keysChanged.push_back(e.code);
          taken.keyWentDown = taken.keyWentDown || (e.down && !isModifierKey(e.code));
          s.keysDown[std::size_t(e.code)] = e.down;
        }
        break;
      }
    }
  }
  return s;
}

}  // namespace hermite::app
