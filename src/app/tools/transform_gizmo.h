#pragma once
// The transform gizmo drawn with ImGui draw lists about the pivot (the transformed centroid of
// the samples): translate arrows along the world axes, rotation rings about them, a uniform-scale
// handle. A drag edits the scene's similarity transform; every drag is one undo step.

#include <optional>
#include <vector>

#include "app/gui/gui_context.h"

namespace hermite::app {

class TransformGizmo {
 public:
  explicit TransformGizmo(GuiContext& ctx) : ctx_(ctx) {}
  void draw() const;
  // A press at `mouse` (view pixels) grabs the handle under it; false when there is none.
  bool press(const Vec<2>& mouse);
  void drag(const Vec<2>& mouse);

 private:
  struct Handle {
    enum Kind { Translate, Rotate, Scale } kind = Translate;
    int axis = 0;
  };
  std::optional<Handle> pick(const Vec<2>& mouse) const;
  std::vector<Handle> handles() const;
  std::vector<Vec<2>> shape(const Handle& h) const;  // the handle's polyline in view pixels
  bool frame(Vec<3>& pivot, double& size) const;      // pivot and size in world units
  std::optional<Vec<2>> worldToView(const Vec<3>& x) const;

  GuiContext& ctx_;
  Handle grabbed_;
  Vec<2> lastMouse_ = Vec<2>::Zero();
};

}  // namespace hermite::app
