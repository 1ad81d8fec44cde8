#pragma once
// The Diagnostics window (top right): what the shown result is — solver, unknowns, condition,
// residuals, view timing and warnings for a fit; the stage and holes for hole filling; the patch
// grid and its error — and the running fit's progress with Cancel.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawDiagnosticsPanel(GuiContext& ctx);

}  // namespace hermite::app
