#include "app/gui/view_legends.h"

#include <imgui.h>

#include "app/gui/gui_context.h"
#include "app/gui/view_colours.h"
#include "core/trace/shading.h"
#include "render/legend.h"
#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

render::LegendOptions heatMapBar(const SceneViewResult& view, const char* title, float cornerX, float cornerY) {
  render::LegendOptions bar;
  bar.range = view.colourRange;
  bar.isoSpacing = view.isoSpacing;
  bar.title = title;
  bar.cornerX = cornerX;
  bar.cornerY = cornerY;
  return bar;
}

}  // namespace

void drawViewLegends(const GuiContext& ctx, const SceneViewResult& view) {
  ImDrawList* list = ImGui::GetBackgroundDrawList();
  const float x = float(ctx.view.x + ctx.view.primaryWidth()), y = float(ctx.view.y + ctx.view.h);
  const Scene& scene = ctx.scene();
  switch (scene.mode) {
    case SceneMode::Implicit2d:
      if (view.colourRange > 0) render::drawColorLegend(list, heatMapBar(view, "f", x, y));
      return;
    case SceneMode::Implicit3d: {
      float top = y;
      if (scene.view.slice.enabled && view.colourRange > 0) {
        render::LegendOptions bar = heatMapBar(view, "f on the slice", x, y);
        bar.barHeight = 90;
        top = render::drawColorLegend(list, bar);
      }
      render::drawSwatchLegend(list, {{shading::kFrontColor, "surface, seen from outside"},
                                      {shading::kBackColor, "surface, seen from inside"}},
                               x, top);
      return;
    }
    case SceneMode::Patch: {
      const FitOutcome* f = ctx.currentFit();
      const PatchDisplay* patch = f ? f->as<PatchDisplay>() : nullptr;
      if (!patch || !scene.patch.showError || patch->vertexError.empty() || !(patch->maxError > 0)) return;
      render::LegendOptions bar;
      bar.title = "error vs torus";
      bar.range = patch->maxError;
      bar.ramp = std::array<render::LegendColour, 2>{shading::kFrontColor, kPatchErrorColour};
      bar.cornerX = x;
      bar.cornerY = y;
      render::drawColorLegend(list, bar);
      return;
    }
    case SceneMode::HoleFill:
      render::drawSwatchLegend(list, {{shading::kFrontColor, "input mesh"}, {kHolePatchColour, "added triangles"},
                                      {kHoleRimColour, "hole rims"}, {kRingNormalColour, "ring samples (normals)"}},
                               x, y);
      return;
  }
}

}  // namespace hermite::app
