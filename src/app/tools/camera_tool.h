#pragma once
// The camera moved by the mouse and the keyboard: orbit about the target, pan, zoom towards the
// cursor, fit the shown data (or mesh) to the view, reset to Home. Each move is a camera change
// of the document (not an undo step).

#include "app/gui/gui_context.h"

namespace hermite::app {

class CameraTool {
 public:
  explicit CameraTool(GuiContext& ctx) : ctx_(ctx) {}
  void orbit(double dx, double dy);  // mouse motion in pixels
  void pan(double dx, double dy);
  void zoom(double notches, const Vec<2>& mouse);  // + = towards the point under `mouse` (view pixels)
  void fitToView();
  void resetView();

 private:
  GuiContext& ctx_;
};

}  // namespace hermite::app
