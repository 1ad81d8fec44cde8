#pragma once
// Colour legends, drawn into an ImGui draw list (so they render through the ImGui renderer in a
// window and offscreen alike). Needs a current ImGui context between NewFrame and Render. Sizes
// follow the UI type: they are given for the 13 px font (ui_font.h) and scale with the font size.
//  - a colour bar with values: the diverging map of f (core/trace/color_map.h) for the 2D field
//    and the slice plane, inside (f < 0) at the bottom, outside (f > 0) at the top; or a ramp
//    between two colours from 0 to a maximum (the patch error);
//  - swatches: a box of colours and their meanings (the 3D surface seen from outside / inside).

#include <array>
#include <optional>
#include <string>
#include <vector>

struct ImDrawList;

namespace hermite::render {

using LegendColour = std::array<double, 3>;  // linear RGB in [0, 1]

struct LegendOptions {
  double range = 1.0;        // the bar covers [−range, range] (a ramp: [0, range])
  double isoSpacing = 0.0;   // > 0: ticks at the iso-line values
  std::string title = "f";
  float barWidth = 14.0f;    // pixels at 13 px type
  float barHeight = 0.0f;    // pixels at 13 px type; 0 = 40 % of the corner's height, 40 to 220 (× type scale)
  float margin = 8.0f;       // from the bottom-right corner (pixels at 13 px type)
  // The bottom-right corner it sits in (pixels); (0, 0) = the display's (ImGui DisplaySize).
  float cornerX = 0.0f, cornerY = 0.0f;
  bool insideOutside = true;  // diverging bar: "inside" / "outside" beside the ends
  // Set: a ramp from first (0) to second (range) instead of the diverging map.
  std::optional<std::array<LegendColour, 2>> ramp;
};

// Draws the bar in the corner; returns the top of its box (pixels), where another legend can sit.
float drawColorLegend(ImDrawList* list, const LegendOptions& options);

struct LegendSwatch {
  LegendColour colour;
  std::string label;
};

// Draws the swatches stacked in a box whose bottom-right corner is (cornerX, cornerY) less the
// margin; returns the top of the box.
float drawSwatchLegend(ImDrawList* list, const std::vector<LegendSwatch>& swatches, float cornerX, float cornerY,
                       float margin = 8.0f);

}  // namespace hermite::render
