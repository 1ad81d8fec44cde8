#pragma once
// The partition-of-unity leaves over the view (View > partition boxes): each leaf's box (its
// support shrunk by its factor) in the model's frame mapped to the world, as ImGui lines.

#include "app/gui/gui_context.h"

namespace hermite::app {

void drawPartitionBoxes(const GuiContext& ctx);

}  // namespace hermite::app
