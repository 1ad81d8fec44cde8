#include "app/gui/axes_overlay.h"

#include <imgui.h>

#include <utility>

#include "app/tools/spec_vectors.h"

namespace hermite::app {

namespace {

constexpr float kAxisLengthPx = 36.0f;   // a unit axis facing the screen
constexpr float kCornerOffsetPx = 52.0f; // the gizmo's centre from the view's lower-left corner

}  // namespace

void drawAxesGizmo(const GuiContext& ctx) {
  const Scene& s = ctx.scene();
  if (!s.view.showAxes || s.mode == SceneMode::Implicit2d) return;
  const CameraSpec& c = s.view.camera;
  // The camera basis: forward f, right r, screen-up u (look-at, as the renderer builds it).
  const Vec<3> f = (toVec(c.target) - toVec(c.eye)).normalized();
  const Vec<3> r = f.cross(toVec(c.up)).normalized();
  const Vec<3> u = r.cross(f);
  const ImVec2 o(float(ctx.view.x) + kCornerOffsetPx, float(ctx.view.y + ctx.view.h) - kCornerOffsetPx);
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImU32 colours[3] = {IM_COL32(220, 50, 50, 255), IM_COL32(40, 170, 40, 255), IM_COL32(50, 90, 230, 255)};
  const char* names[3] = {"x", "y", "z"};
  // Farthest axis first, so the nearer ones draw over it.
  int order[3] = {0, 1, 2};
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (f(order[j]) > f(order[i])) std::swap(order[i], order[j]);
  for (int k : order) {
    const ImVec2 tip(o.x + kAxisLengthPx * float(r(k)), o.y - kAxisLengthPx * float(u(k)));
    dl->AddLine(o, tip, colours[k], 2.5f);
    dl->AddText(ImVec2(tip.x + 2, tip.y - 7), colours[k], names[k]);
  }
}

}  // namespace hermite::app
