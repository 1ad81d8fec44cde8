#pragma once
// The colour legend of the 2D field view and the slice plane: a vertical bar of the diverging
// colour map (core/trace/color_map.h) with its values, drawn into an ImGui draw list (so it renders
// through the ImGui renderer in a window and offscreen alike). Needs a current ImGui context
// between NewFrame and Render.

#include <string>

struct ImDrawList;

namespace hermite::render {

struct LegendOptions {
  double range = 1.0;        // the bar covers [−range, range]
  double isoSpacing = 0.0;   // > 0: ticks at the iso-line values
  std::string title = "f";
  float barWidth = 14.0f;    // pixels
  float barHeight = 0.0f;    // pixels; 0 = 40 % of the display height, between 40 and 220
  float margin = 8.0f;       // from the bottom-right corner
  // The bottom-right corner it sits in (pixels); (0, 0) = the display's (ImGui DisplaySize).
  float cornerX = 0.0f, cornerY = 0.0f;
};

// Draws the legend at the bottom-right corner of the display (ImGui::GetIO().DisplaySize).
void drawColorLegend(ImDrawList* list, const LegendOptions& options);

}  // namespace hermite::render
