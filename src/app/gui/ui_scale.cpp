#include "app/gui/ui_scale.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace hermite::app {

float clampUiScale(float scale) {
  if (!std::isfinite(scale) || scale <= 0) return 1.0f;
  return std::clamp(scale, kMinUiScale, kMaxUiScale);
}

float stepUiScale(float scale, int steps) {
  // Snap to the grid of steps first, so 1.1 goes to 1.25 and 1.0, not to 1.35 and 0.85.
  const float grid = steps > 0 ? std::floor(scale / kUiScaleStep + 1e-3f) : std::ceil(scale / kUiScaleStep - 1e-3f);
  return clampUiScale((grid + float(steps)) * kUiScaleStep);
}

void applyUiStyle(float scale) {
  ImGuiStyle style;
  ImGui::StyleColorsDark(&style);
  style.WindowRounding = 3.0f;
  style.ScaleAllSizes(scale);
  ImGui::GetStyle() = style;
}

}  // namespace hermite::app
