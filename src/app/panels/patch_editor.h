#pragma once
// The patch editor (mode "patch"): the Patch panel and the handles in the view, grabbed and
// dragged on the plane through the handle facing the camera (X, Y or Z held: along that axis).

#include <optional>

#include "app/gui/gui_context.h"
#include "app/gui/gui_input.h"

namespace hermite::app {

class PatchEditor {
 public:
  explicit PatchEditor(GuiContext& ctx) : ctx_(ctx) {}
  void drawPanel();
  void drawHandles() const;
  // Screen position (view pixels) of a handle of the document's patch; nullopt if behind.
  std::optional<Vec<2>> handlePosition(const PatchHandle& h) const;
  // A press at `mouse` grabs the handle under it; false when there is none.
  bool press(const Vec<2>& mouse);
  void drag(const Vec<2>& mouse, const FrameInput& in);

 private:
  GuiContext& ctx_;
  PatchHandle grabbed_;
  Vec<3> grabStart_ = Vec<3>::Zero();
};

}  // namespace hermite::app
