#pragma once
// The samples edited in the view: select and drag a sample (3D: on the plane through it facing
// the camera), rotate its normal by the tip, add one (Ctrl+click: 2D at the cursor, 3D on the
// surface or the slice plane, normal from ∇f), flip or delete the selected one. The first edit
// makes a preset or file scene's samples inline; edits apply before the scene's transform.

#include <optional>

#include "app/gui/gui_context.h"

namespace hermite::app {

class SampleTool {
 public:
  explicit SampleTool(GuiContext& ctx) : ctx_(ctx) {}

  // Position of sample i and of its normal's tip in view pixels; nullopt when not visible.
  std::optional<Vec<2>> samplePosition(int i) const;
  std::optional<Vec<2>> normalTipPosition(int i) const;
  // A press at `mouse`: grabs the selected sample or its normal's tip under it (anySample: any
  // sample, which becomes selected) and starts the drag gesture; false when there is none.
  bool press(const Vec<2>& mouse, bool anySample);
  // The sample drawn under `mouse` (view pixels), −1 for none.
  int sampleAt(const Vec<2>& mouse) const;
  void drag(const Vec<2>& mouse);  // the grabbed sample or tip follows the mouse
  void addAt(const Vec<2>& mouse);
  void deleteSelected();
  void flipSelected();
  // The selected sample's ring and normal handle (background draw list).
  void drawSelection() const;

 private:
  std::optional<Vec<2>> position(int i, bool tip) const;
  int pick(const Vec<2>& mouse, bool* onTip) const;
  void move(const Vec<2>& mouse, bool tip);
  template <int Dim, class Target>
  void moveTo(bool tip, Target target);
  void addAt3d(const Vec<2>& mouse, const FitOutcome& fit);

  GuiContext& ctx_;
  Vec<3> dragPlanePoint_ = Vec<3>::Zero();  // 3D drags move on the plane through it facing the camera
};

}  // namespace hermite::app
