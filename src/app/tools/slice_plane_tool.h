#pragma once
// The 3D slice plane dragged along its normal (Alt + left drag): the grabbed point slides on the
// line through it along the normal, and the offset follows the line parameter nearest to the
// mouse ray; where the normal points along the ray, vertical mouse motion moves it instead.

#include <optional>

#include "app/gui/gui_context.h"

namespace hermite::app {

// Offsets in [−extent, extent] cut the view bounds of the shown 3D fit (2 without one).
double sliceOffsetExtent(const GuiContext& ctx);

class SlicePlaneTool {
 public:
  explicit SlicePlaneTool(GuiContext& ctx) : ctx_(ctx) {}
  // A press at `mouse` (view pixels) grabs the plane when it is shown; false otherwise.
  bool press(const Vec<2>& mouse);
  void drag(const Vec<2>& mouse);

 private:
  std::optional<double> lineParameter(const Vec<2>& mouse) const;

  GuiContext& ctx_;
  struct Grab {
    Vec<3> point = Vec<3>::Zero();        // on the plane, world units
    double offset = 0;                    // view.slice.offset at the press
    std::optional<double> lineParameter;  // at the press; none when the normal points along the ray
    double pressY = 0;                    // view pixels, for the fallback (vertical mouse motion)
  } grab_;
};

}  // namespace hermite::app
