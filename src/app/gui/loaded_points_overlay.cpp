#include "app/gui/loaded_points_overlay.h"

#include <imgui.h>

#include <algorithm>
#include <optional>

#include "app/gui/scene_view.h"

namespace hermite::app {

bool loadedPointsPending(const GuiContext& ctx) {
  if (!ctx.loadedData || !ctx.loadedData->points || ctx.loadedData->data != ctx.scene().data) return false;
  const FitOutcome* shown = ctx.fits.shown().get();
  return !shown || shown->scene.data != ctx.loadedData->data || shown->scene.mode != ctx.scene().mode;
}

void drawLoadedPoints(const GuiContext& ctx) {
  if (!loadedPointsPending(ctx)) return;
  const Eigen::MatrixXd& P = *ctx.loadedData->points;  // Dim × N
  const int w = ctx.view.primaryWidth(), h = ctx.view.h;
  if (w < 1 || h < 1 || P.cols() == 0 || P.rows() != ctx.dimension()) return;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const Vec<2> o = ctx.view.origin();
  const auto& bg = ctx.scene().view.background;
  dl->AddRectFilled(ImVec2(float(o.x()), float(o.y())), ImVec2(float(o.x() + w), float(o.y() + h)),
                    IM_COL32(int(255 * bg[0]), int(255 * bg[1]), int(255 * bg[2]), 255));
  const ImU32 colour = IM_COL32(40, 90, 200, 255);
  const Eigen::Index stride = std::max<Eigen::Index>(1, (P.cols() + kMaxLoadedPointsDrawn - 1) / kMaxLoadedPointsDrawn);
  const auto dot = [&](const Vec<2>& p) {
    if (p.x() < 0 || p.y() < 0 || p.x() > w || p.y() > h) return;
    const float x = float(p.x() + o.x()), y = float(p.y() + o.y());
    dl->AddRectFilled(ImVec2(x - 1.0f, y - 1.0f), ImVec2(x + 1.0f, y + 1.0f), colour);
  };
  if (P.rows() == 2) {
    const View2d view = sceneView2d(ctx.scene(), w, h);
    for (Eigen::Index i = 0; i < P.cols(); i += stride) dot(view.worldToPixel(P.col(i)));
  } else {
    const Camera cam = sceneCamera(ctx.scene(), w, h);
    for (Eigen::Index i = 0; i < P.cols(); i += stride)
      if (const std::optional<Vec<2>> p = cam.projectVisible(Vec<3>(P.col(i)))) dot(*p);
  }
  const char* note = "fitting the loaded points...";
  dl->AddText(ImVec2(float(o.x() + 10), float(o.y() + h - 24)), IM_COL32(60, 60, 60, 255), note);
}

}  // namespace hermite::app
