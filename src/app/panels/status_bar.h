#pragma once
// The status bar along the bottom: the document's file (with * when modified) and the last
// message, red for errors.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawStatusBar(const GuiContext& ctx);

}  // namespace hermite::app
