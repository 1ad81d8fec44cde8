#pragma once
// The axes gizmo (`view.show_axes`): the world x, y and z axes as seen by the 3D camera, drawn
// as red, green and blue ImGui lines in the view's lower-left corner, so that the orientation of
// the model stays readable while orbiting.

#include "app/gui/gui_context.h"

namespace hermite::app {

// Draws the gizmo when the scene asks for it and the mode is 3D (implicit3d, patch, holefill).
void drawAxesGizmo(const GuiContext& ctx);

}  // namespace hermite::app
