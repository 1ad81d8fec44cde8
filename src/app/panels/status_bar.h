#pragma once
// The status bar along the bottom, two lines tall: on the left the document's file (with * when
// modified), on the right the last message (red for errors) wrapped over both lines; a longer
// message ends in "…" and shows in full while hovered and in the message log ("log" button, F2).

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawStatusBar(GuiContext& ctx);

}  // namespace hermite::app
