#include "render/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/trace/color_map.h"
#include "render/ui_font.h"

namespace hermite::render {

namespace {

constexpr ImU32 kBoxFill = IM_COL32(255, 255, 255, 220), kBoxEdge = IM_COL32(90, 90, 90, 255);
constexpr ImU32 kInk = IM_COL32(20, 20, 20, 255);

ImU32 toColour(const Vec<3>& c) {
  return IM_COL32(int(std::lround(255 * c(0))), int(std::lround(255 * c(1))), int(std::lround(255 * c(2))), 255);
}
ImU32 toColour(const LegendColour& c) { return toColour(Vec<3>(c[0], c[1], c[2])); }

std::string label(double v, bool ramp) {
  char buf[32];
  if (v == 0 || std::abs(v) < 1e-12) return "0";
  std::snprintf(buf, sizeof buf, ramp ? "%.3g" : "%+.3g", v);
  return buf;
}

// The type's scale relative to the 13 px design size.
float typeScale() { return ImGui::GetFontSize() / kUiFontPixels; }

// The bar itself in [x0, x1] × [y0, y1]: the diverging map (exact: it is piecewise linear between
// its stops, one gradient quad per interval) or the two-colour ramp.
void drawBar(ImDrawList* list, const LegendOptions& o, float x0, float x1, float y0, float y1) {
  const float barH = y1 - y0;
  if (o.ramp) {
    const ImU32 lo = toColour((*o.ramp)[0]), hi = toColour((*o.ramp)[1]);
    list->AddRectFilledMultiColor(ImVec2(x0, y0), ImVec2(x1, y1), hi, hi, lo, lo);
  } else {
    for (std::size_t k = 0; k + 1 < kDivergingStops.size(); ++k) {
      const double ta = kDivergingStops[k].t, tb = kDivergingStops[k + 1].t;  // ta < tb, bottom to top
      const float ya = y1 - float((ta + 1) / 2) * barH, yb = y1 - float((tb + 1) / 2) * barH;
      const ImU32 ca = toColour(divergingColorAt(ta)), cb = toColour(divergingColorAt(tb));
      list->AddRectFilledMultiColor(ImVec2(x0, yb), ImVec2(x1, ya), cb, cb, ca, ca);
    }
  }
  list->AddRect(ImVec2(x0 - 1, y0 - 1), ImVec2(x1 + 1, y1 + 1), IM_COL32(60, 60, 60, 255));
}

}  // namespace

float drawColorLegend(ImDrawList* list, const LegendOptions& options) {
  const ImVec2 corner = options.cornerX > 0 && options.cornerY > 0 ? ImVec2(options.cornerX, options.cornerY)
                                                                    : ImGui::GetIO().DisplaySize;
  const float s = typeScale(), fontH = ImGui::GetFontSize(), pad = 4.0f * s;
  const float barW = options.barWidth * s;
  const float barH = options.barHeight > 0 ? options.barHeight * s : std::clamp(0.4f * corner.y, 40.0f * s, 220.0f * s);
  const double range = options.range > 0 ? options.range : 1.0;
  const bool ramp = options.ramp.has_value(), words = options.insideOutside && !ramp;
  const std::string top = label(range, ramp) + (words ? "  outside" : ""),
                    bottom = (ramp ? "0" : label(-range, ramp)) + (words ? "  inside" : "");
  const float labelW = std::max({ImGui::CalcTextSize(top.c_str()).x, ImGui::CalcTextSize(bottom.c_str()).x,
                                 ImGui::CalcTextSize(options.title.c_str()).x - barW - pad});
  // Box: title on top, bar on the left, labels on the right.
  const float boxW = pad + barW + pad + labelW + pad;
  const float boxH = pad + fontH + pad + barH + pad + 0.5f * fontH;
  const ImVec2 boxMax(std::floor(corner.x - options.margin * s), std::floor(corner.y - options.margin * s));
  const ImVec2 boxMin(boxMax.x - boxW, boxMax.y - boxH);
  list->AddRectFilled(boxMin, boxMax, kBoxFill, 3.0f * s);
  list->AddRect(boxMin, boxMax, kBoxEdge, 3.0f * s);
  list->AddText(ImVec2(boxMin.x + pad, boxMin.y + pad), kInk, options.title.c_str());

  const float x0 = boxMin.x + pad, x1 = x0 + barW;
  const float y0 = boxMin.y + pad + fontH + pad, y1 = y0 + barH;
  drawBar(list, options, x0, x1, y0, y1);
  const auto tick = [&](double t, const std::string& text) {  // t in [0, 1], bottom to top
    const float y = std::round(y1 - float(t) * barH);
    list->AddLine(ImVec2(x1, y), ImVec2(x1 + 3 * s, y), IM_COL32(40, 40, 40, 255));
    if (!text.empty()) list->AddText(ImVec2(x1 + pad, y - 0.5f * fontH), kInk, text.c_str());
  };
  if (!ramp && options.isoSpacing > 0 && range / options.isoSpacing < 40)
    for (int k = -int(range / options.isoSpacing); k <= int(range / options.isoSpacing); ++k)
      tick((k * options.isoSpacing / range + 1) / 2, "");
  tick(1, top);
  tick(0.5, ramp ? label(0.5 * range, true) : "0");
  tick(0, bottom);
  if (!ramp) {  // the zero curve's colour (outside the map) at the 0 tick
    const float yz = std::round(y1 - 0.5f * barH);
    list->AddLine(ImVec2(x0 - 1, yz), ImVec2(x1 + 1, yz), IM_COL32(0, 0, 0, 255), 2.0f * s);
  }
  return boxMin.y;
}

float drawSwatchLegend(ImDrawList* list, const std::vector<LegendSwatch>& swatches, float cornerX, float cornerY,
                       float margin) {
  const float s = typeScale(), fontH = ImGui::GetFontSize(), pad = 4.0f * s, box = fontH;
  float labelW = 0;
  for (const LegendSwatch& w : swatches) labelW = std::max(labelW, ImGui::CalcTextSize(w.label.c_str()).x);
  const float rowH = fontH + pad;
  const ImVec2 boxMax(std::floor(cornerX - margin * s), std::floor(cornerY - margin * s));
  const ImVec2 boxMin(boxMax.x - (pad + box + pad + labelW + pad), boxMax.y - (pad + rowH * float(swatches.size())));
  list->AddRectFilled(boxMin, boxMax, kBoxFill, 3.0f * s);
  list->AddRect(boxMin, boxMax, kBoxEdge, 3.0f * s);
  float y = boxMin.y + pad;
  for (const LegendSwatch& w : swatches) {
    const ImVec2 a(boxMin.x + pad, y), b(boxMin.x + pad + box, y + box);
    list->AddRectFilled(a, b, toColour(w.colour));
    list->AddRect(a, b, IM_COL32(60, 60, 60, 255));
    list->AddText(ImVec2(b.x + pad, y), kInk, w.label.c_str());
    y += rowH;
  }
  return boxMin.y;
}

}  // namespace hermite::render
