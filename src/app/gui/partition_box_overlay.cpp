#include "app/gui/partition_box_overlay.h"

#include <imgui.h>

#include <algorithm>
#include <optional>

#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

constexpr std::size_t kMaxBoxes = 4000;  // beyond this the lines only hide the view

// Each leaf's box edges (corners i and i | bit, in the model's frame mapped to the world),
// through `toView` (world → view pixels, none when not visible), as lines offset by `o`.
template <int Dim, class ToView>
void drawBoxes(const PuModel<Dim>& pu, ToView toView, const Vec<2>& o) {
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImU32 colour = IM_COL32(90, 60, 160, 170);
  for (std::size_t k = 0; k < std::min(pu.leaves().size(), kMaxBoxes); ++k) {
    const auto& leaf = pu.leaves()[k];
    const Vec<Dim> c = leaf.support.center(), h = 0.5 * leaf.support.extent() / leaf.factor;
    const auto corner = [&](int i) {
      Vec<Dim> x = c;
      for (int d = 0; d < Dim; ++d) x(d) += (i >> d & 1) ? h(d) : -h(d);
      return toView(pu.frame().apply(x));
    };
    for (int i = 0; i < (1 << Dim); ++i)
      for (int bit = 1; bit < (1 << Dim); bit <<= 1) {
        if (i & bit) continue;
        const std::optional<Vec<2>> a = corner(i), b = corner(i | bit);
        if (!a || !b) continue;
        dl->AddLine(ImVec2(float(a->x() + o.x()), float(a->y() + o.y())),
                    ImVec2(float(b->x() + o.x()), float(b->y() + o.y())), colour, 1.0f);
      }
  }
}

}  // namespace

void drawPartitionBoxes(const GuiContext& ctx) {
  const FitOutcome* f = ctx.fits.shown().get();
  if (!f) return;
  const int w = ctx.view.primaryWidth(), h = ctx.view.h;
  if (const auto* f2 = f->as<SceneFit<2>>(); f2 && f2->pu()) {
    const View2d view = sceneView2d(ctx.scene(), w, h);
    drawBoxes<2>(*f2->pu(), [&](const Vec<2>& x) { return std::optional<Vec<2>>(view.worldToPixel(x)); }, ctx.view.origin());
  } else if (const auto* f3 = f->as<SceneFit<3>>(); f3 && f3->pu()) {
    const Camera cam = sceneCamera(ctx.scene(), w, h);
    drawBoxes<3>(*f3->pu(), [&](const Vec<3>& x) { return cam.projectVisible(x); }, ctx.view.origin());
  }
}

}  // namespace hermite::app
