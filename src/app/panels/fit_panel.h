#pragma once
// The Fit section: method, kernel, r (a logarithmic slider, one undo step per drag, and exact
// entry, with r in units of the mean sample spacing), polynomial, smoothing, the RBF offset and
// the partition of unity; the last fit's error.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawFitPanel(GuiContext& ctx);

}  // namespace hermite::app
