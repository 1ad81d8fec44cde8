#include "render/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "core/trace/color_map.h"

namespace hermite::render {

namespace {

ImU32 mapColor(double t) {
  const Vec<3> c = divergingColorAt(t);
  return IM_COL32(int(std::lround(255 * c(0))), int(std::lround(255 * c(1))), int(std::lround(255 * c(2))), 255);
}

std::string label(double v) {
  char buf[32];
  if (v == 0 || std::abs(v) < 1e-12) return "0";
  std::snprintf(buf, sizeof buf, "%+.3g", v);
  return buf;
}

}  // namespace

void drawColorLegend(ImDrawList* list, const LegendOptions& options) {
  const ImVec2 display = options.cornerX > 0 && options.cornerY > 0 ? ImVec2(options.cornerX, options.cornerY)
                                                                     : ImGui::GetIO().DisplaySize;
  const float barH = options.barHeight > 0 ? options.barHeight : std::clamp(0.4f * display.y, 40.0f, 220.0f);
  const float fontH = ImGui::GetFontSize();
  const double range = options.range > 0 ? options.range : 1.0;
  const std::string top = label(range), bottom = label(-range);
  const float labelW = std::max({ImGui::CalcTextSize(top.c_str()).x, ImGui::CalcTextSize(bottom.c_str()).x,
                                 ImGui::CalcTextSize(options.title.c_str()).x});
  const float pad = 4.0f;
  // Box: title on top, bar on the left, labels on the right.
  const float boxW = pad + options.barWidth + pad + labelW + pad;
  const float boxH = pad + fontH + pad + barH + pad + 0.5f * fontH;
  const ImVec2 boxMax(std::floor(display.x - options.margin), std::floor(display.y - options.margin));
  const ImVec2 boxMin(boxMax.x - boxW, boxMax.y - boxH);
  list->AddRectFilled(boxMin, boxMax, IM_COL32(255, 255, 255, 220), 3.0f);
  list->AddRect(boxMin, boxMax, IM_COL32(90, 90, 90, 255), 3.0f);
  const ImU32 text = IM_COL32(20, 20, 20, 255);
  list->AddText(ImVec2(boxMin.x + pad, boxMin.y + pad), text, options.title.c_str());

  const float x0 = boxMin.x + pad, x1 = x0 + options.barWidth;
  const float y0 = boxMin.y + pad + fontH + pad, y1 = y0 + barH;
  // The map is piecewise linear between its stops, so one gradient quad per stop interval is exact.
  for (std::size_t k = 0; k + 1 < kDivergingStops.size(); ++k) {
    const double ta = kDivergingStops[k].t, tb = kDivergingStops[k + 1].t;  // ta < tb, bottom to top
    const float ya = y1 - float((ta + 1) / 2) * barH, yb = y1 - float((tb + 1) / 2) * barH;
    const ImU32 ca = mapColor(ta), cb = mapColor(tb);
    list->AddRectFilledMultiColor(ImVec2(x0, yb), ImVec2(x1, ya), cb, cb, ca, ca);
  }
  list->AddRect(ImVec2(x0 - 1, y0 - 1), ImVec2(x1 + 1, y1 + 1), IM_COL32(60, 60, 60, 255));

  const auto tick = [&](double v, const std::string& s, bool withLabel) {
    const float y = std::round(y1 - float((v / range + 1) / 2) * barH);
    list->AddLine(ImVec2(x1, y), ImVec2(x1 + 3, y), IM_COL32(40, 40, 40, 255));
    if (withLabel) list->AddText(ImVec2(x1 + pad, y - 0.5f * fontH), text, s.c_str());
  };
  if (options.isoSpacing > 0 && range / options.isoSpacing < 40)
    for (int k = -int(range / options.isoSpacing); k <= int(range / options.isoSpacing); ++k)
      tick(k * options.isoSpacing, "", false);
  tick(range, top, true);
  tick(0, "0", true);
  tick(-range, bottom, true);
  // The zero curve's colour (outside the map) next to the 0 label.
  const float yz = std::round(y1 - 0.5f * barH);
  list->AddLine(ImVec2(x0 - 1, yz), ImVec2(x1 + 1, yz), IM_COL32(0, 0, 0, 255), 2.0f);
}

}  // namespace hermite::render
