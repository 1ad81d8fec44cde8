#pragma once
// Presenter mode (F5, view.presenter): the panels and the status bar are hidden and a caption in
// large type names what the view shows — method, kernel, r (also in mean sample spacings),
// polynomial and N for an implicit fit; the patch grid or the hole-filling stage otherwise — at
// the bottom of the view, readable from the back of a lecture room.

#include <string>

#include "app/gui/gui_context.h"

struct ImFont;

namespace hermite::app {

// The caption's text for the scene and fit on screen (one line).
std::string presenterCaption(const GuiContext& ctx);

// Draws the caption in `font` (the large UI font) centred at the bottom of the view.
void drawPresenterCaption(const GuiContext& ctx, ImFont* font);

}  // namespace hermite::app
