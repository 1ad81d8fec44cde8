#pragma once
// The Controls window (F1 or ?): every mouse gesture and shortcut of the view.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawHelpOverlay(GuiContext& ctx);

}  // namespace hermite::app
