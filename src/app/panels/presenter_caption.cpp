#include "app/panels/presenter_caption.h"

#include <imgui.h>

#include <cstdio>
#include <type_traits>

#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

std::string number(const char* format, double v) {
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// "HRBF · wendland · r = 0.6 (2.4 × spacing) · linear · N = 40"
std::string implicitCaption(const Scene& s, const FitOutcome* fit) {
  const FitSpec& f = s.fit;
  std::string text = std::string(fitMethodName(f.method)) + " \xC2\xB7 " + std::string(kernelName(f.kernel));
  int samples = 0;
  double spacing = 0;
  if (fit)
    fit->visitImplicit([&](const auto& fitted) {
      samples = int(fitted.samples.points.cols());
      spacing = fit->sampleSpacing();
    });
  if (Kernel{f.kernel, f.radius}.usesRadius()) {
    text += " \xC2\xB7 r = " + number("%.3g", f.radius);
    if (spacing > 0) text += " (" + number("%.3g", f.radius / spacing) + " \xC3\x97 spacing)";
  }
  text += " \xC2\xB7 " + std::string(polynomialName(f.polynomial)) + " polynomial";
  if (samples > 0) text += " \xC2\xB7 N = " + std::to_string(samples);
  return text;
}

}  // namespace

std::string presenterCaption(const GuiContext& ctx) {
  const Scene& s = ctx.scene();
  switch (s.mode) {
    case SceneMode::Implicit2d:
    case SceneMode::Implicit3d: return implicitCaption(s, ctx.currentFit());
    case SceneMode::Patch:
      return "Hermite patches \xC2\xB7 " + std::to_string(s.patch.splits[0]) + " \xC3\x97 " +
             std::to_string(s.patch.splits[1]) + " \xC2\xB7 " + std::string(patchFormName(s.patch.form)) + " form";
    case SceneMode::HoleFill: return "hole filling \xC2\xB7 stage: " + std::string(holeFillStageName(s.holefill.stage));
  }
  return s.sourceName;
}

void drawPresenterCaption(const GuiContext& ctx, ImFont* font) {
  if (!font) return;
  const std::string text = presenterCaption(ctx);
  ImDrawList* list = ImGui::GetForegroundDrawList();
  const float size = font->FontSize, pad = 0.4f * size;
  const float maxWidth = float(ctx.view.w) - 4 * pad;
  const ImVec2 extent = font->CalcTextSizeA(size, maxWidth, maxWidth, text.c_str());
  const float x = float(ctx.view.x) + 0.5f * (float(ctx.view.w) - extent.x);
  const float y = float(ctx.view.y + ctx.view.h) - extent.y - 2 * pad;
  list->AddRectFilled(ImVec2(x - pad, y - pad), ImVec2(x + extent.x + pad, y + extent.y + pad), IM_COL32(0, 0, 0, 190),
                      0.3f * pad);
  list->AddText(font, size, ImVec2(x, y), IM_COL32(255, 255, 255, 255), text.c_str(), nullptr, maxWidth);
}

}  // namespace hermite::app
