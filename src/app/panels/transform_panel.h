#pragma once
// The Transform section of the left panel.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawTransformPanel(GuiContext& ctx);

}  // namespace hermite::app
