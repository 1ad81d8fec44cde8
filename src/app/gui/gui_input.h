#pragma once
// One frame of input as the window (GLFW callbacks) or a test script delivers it, and how it
// reaches ImGui.

#include <array>
#include <string>
#include <vector>

namespace hermite::app {

// One frame of input, in framebuffer pixels (row 0 = top). Key codes are GLFW's.
struct FrameInput {
  int width = 800, height = 600;
  double mouseX = -1, mouseY = -1;        // < 0: no mouse over the window
  std::array<bool, 3> mouseDown{};        // left, right, middle
  float wheel = 0;                        // notches this frame, + = away from the user
  std::array<bool, 512> keysDown{};       // GLFW key codes
  bool ctrl = false, shift = false, alt = false;
  std::vector<unsigned> characters;       // text input this frame
  std::vector<std::string> droppedFiles;  // paths dropped onto the window this frame
  double deltaSeconds = 1.0 / 60.0;
};

// The current ImGui context reads keys by GLFW key code (ImGui 1.86: KeyMap into KeysDown).
void mapImGuiKeys();
// The frame's size, time, mouse, keys and text into the current ImGui context.
void feedImGui(const FrameInput& in);
// `key` went down this frame (it was up in `previous`).
inline bool keyPressed(const FrameInput& in, const std::array<bool, 512>& previous, int key) {
  return in.keysDown[key] && !previous[key];
}

}  // namespace hermite::app
