#pragma once
// The Compare section: the split view and what its right half fits differently (the RBF-offset
// method, HRBF, another kernel or radius), with the right fit's solver and warnings.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawComparePanel(GuiContext& ctx);

}  // namespace hermite::app
