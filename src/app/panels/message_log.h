#pragma once
// The message log window (F2, the "Messages" box under the panels, the status bar's "log"
// button): every status message and fit warning since the window opened, in full, with its time
// of day and severity, newest last.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawMessageLog(GuiContext& ctx);

}  // namespace hermite::app
