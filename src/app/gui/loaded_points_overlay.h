#pragma once
// The samples of a data file just opened, drawn over the view until a fit of that data is on
// screen (issue 17: the points show at once, while a large fit still runs): the view's background
// over whatever the previous scene left, then one dot per sample (at most kMaxLoadedPointsDrawn,
// evenly strided) through the scene's camera (3D) or 2D view.

#include "app/gui/gui_context.h"

namespace hermite::app {

inline constexpr int kMaxLoadedPointsDrawn = 200000;

// Whether the loaded points stand in for the fit: they describe the scene's data and the fit on
// screen is of other data (or there is none yet).
bool loadedPointsPending(const GuiContext& ctx);
void drawLoadedPoints(const GuiContext& ctx);

}  // namespace hermite::app
