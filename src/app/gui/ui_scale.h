#pragma once
// The UI scale: one factor for the type (rasterised at the scaled pixel size, ui_font.h), ImGui's
// style sizes (padding, spacing, rounding) and the fixed layout (GuiContext::px). 1 is the
// layout as designed for a 96 dpi screen; 2 suits a HiDPI screen or a projector.

namespace hermite::app {

inline constexpr float kMinUiScale = 0.5f;
inline constexpr float kMaxUiScale = 4.0f;
inline constexpr float kUiScaleStep = 0.25f;  // Ctrl + / Ctrl −

// `scale` within [kMinUiScale, kMaxUiScale]; 1 for a value that is not finite or not positive.
float clampUiScale(float scale);
// The scale one Ctrl + (steps = 1) or Ctrl − (steps = −1) away: the next multiple of the step.
float stepUiScale(float scale, int steps);
// The current ImGui context's style: dark colours, the project's rounding, all sizes × scale.
void applyUiStyle(float scale);

}  // namespace hermite::app
