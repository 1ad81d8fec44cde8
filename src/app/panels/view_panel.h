#pragma once
// The View section: the mode, projection, trace mode, slice plane, what is drawn (points,
// normals, bounds, partition boxes), the 2D colour range, the background, fit / reset and stored
// camera views.

#include <vector>

#include "app/gui/gui_context.h"
#include "app/tools/camera_tool.h"

namespace hermite::app {

class ViewPanel {
 public:
  ViewPanel(GuiContext& ctx, CameraTool& camera) : ctx_(ctx), camera_(camera) {}
  void draw();

 private:
  bool drawModeChoice();
  bool draw3dOptions(ViewSpec& v);
  bool drawNormalsChoice(ViewSpec& v);
  bool drawSliceOptions(ViewSpec& v);
  void drawCameraButtons();

  GuiContext& ctx_;
  CameraTool& camera_;
  std::vector<CameraSpec> savedViews_;  // "Store view": numbered buttons return to them
};

}  // namespace hermite::app
