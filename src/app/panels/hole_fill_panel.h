#pragma once
// The hole-filling mode (mode "holefill"): the panel (the mesh, the implicit, the rings, the
// stage shown, each hole's method and result, export) and the holes' numbers in the view.

#include <string>

#include "app/gui/gui_context.h"

namespace hermite::app {

class HoleFillPanel {
 public:
  explicit HoleFillPanel(GuiContext& ctx) : ctx_(ctx) {}
  void draw();
  // Each hole's index at its boundary's centre (background draw list).
  void drawLabels() const;

 private:
  GuiContext& ctx_;
  std::string meshPath_ = "mesh.obj", meshExportPath_ = "filled.glb";
};

}  // namespace hermite::app
