#include "app/panels/view_panel.h"

#include <imgui.h>

#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "app/tools/slice_plane_tool.h"

namespace hermite::app {

void ViewPanel::draw() {
  if (drawModeChoice()) return;
  Scene s = ctx_.scene();
  ViewSpec& v = s.view;
  bool changed = s.mode == SceneMode::Implicit3d && draw3dOptions(v);
  std::string label = "view";
  if (s.mode == SceneMode::Implicit2d || s.mode == SceneMode::Implicit3d) {
    changed |= ImGui::Checkbox("points", &v.showPoints);
    changed |= drawNormalsChoice(v);
  } else {
    const Projection projections[] = {Projection::Perspective, Projection::Orthographic};
    changed |= comboOf("projection", v.projection, projections, projectionName);
  }
  if (s.mode == SceneMode::Implicit2d || s.mode == SceneMode::Implicit3d) {
    ImGui::Checkbox("partition boxes", &ctx_.showPartitionBoxes);
    ctx_.recordWidget("view.partition_boxes");
    helpMarker("The leaves of a partition-of-unity fit (Fit > partition of unity).");
  }
  if (s.mode == SceneMode::Implicit2d) {
    double range = ctx_.colourRange;
    if (ImGui::InputDouble("colour range", &range, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && range >= 0)
      ctx_.colourRange = range;
    helpMarker("The heat map covers [-range, range]; 0 = the largest |f| in the view.");
  }
  float bg[3] = {float(v.background[0]), float(v.background[1]), float(v.background[2])};
  if (ImGui::ColorEdit3("background", bg, ImGuiColorEditFlags_NoInputs)) {
    v.background = {bg[0], bg[1], bg[2]};
    changed = true;
    label = "background";
  }
  if (changed) ctx_.document.apply(s, label);
  drawCameraButtons();
}

// view.show_normals: auto (shown up to kAutoNormalsMaxSamples samples), shown or hidden; true
// when it changed.
bool ViewPanel::drawNormalsChoice(ViewSpec& v) {
  const char* choices[] = {"auto", "shown", "hidden"};
  int choice = !v.showNormals ? 0 : *v.showNormals ? 1 : 2;
  const int before = choice;
  ImGui::Combo("normals", &choice, choices, 3);
  ctx_.recordWidget("view.normals");
  helpMarker("auto: drawn for clouds of up to 1000 samples (view.show_normals).");
  if (choice == before) return false;
  v.showNormals = choice == 0 ? std::optional<bool>() : std::optional<bool>(choice == 1);
  return true;
}

// The mode switch; true when it switched (the rest of the panel waits for the next frame).
bool ViewPanel::drawModeChoice() {
  const SceneMode m = ctx_.scene().mode;
  const char* modes[] = {"2D (implicit2d)", "3D (implicit3d)", "patch editor", "hole filling"};
  const int current = m == SceneMode::Implicit2d ? 0 : m == SceneMode::Patch ? 2 : m == SceneMode::HoleFill ? 3 : 1;
  int mode = current;
  if (ImGui::Combo("mode", &mode, modes, 4) && mode != current) {
    if (mode == 3) {
      Scene n = ctx_.scene();
      n.mode = SceneMode::HoleFill;
      n.view.camera.eye = {1.2, -1.6, 1.4};
      n.view.camera.target = {0, 0, 0};
      n.view.camera.up = {0, 0, 1};
      ctx_.document.apply(n, "hole filling");
    } else if (mode == 2) {
      Scene n = ctx_.scene();
      n.mode = SceneMode::Patch;
      // A view of the default torus piece.
      n.view.camera.eye = {5.0, 3.5, 3.5};
      n.view.camera.target = {2.2, 1.3, 0.4};
      n.view.camera.up = {0, 0, 1};
      ctx_.document.apply(n, "patch editor");
    } else {
      loadPreset(ctx_, mode == 0 ? "curve2d" : "sphere6", mode == 0 ? SceneMode::Implicit2d : SceneMode::Implicit3d);
    }
    return true;
  }
  return false;
}

// Projection, trace mode, slice plane, bounds box: true when `v` changed.
bool ViewPanel::draw3dOptions(ViewSpec& v) {
  bool changed = false;
  const Projection projections[] = {Projection::Perspective, Projection::Orthographic};
  changed |= comboOf("projection", v.projection, projections, projectionName);
  const TraceMode traces[] = {TraceMode::Auto, TraceMode::Baked, TraceMode::Exact};
  changed |= comboOf("trace", v.trace, traces, traceModeName);
  helpMarker("baked: f on a 3D grid, hits refined against the true field when the view settles. exact: the "
             "model summed per pixel in the shader (slow without a GPU).");
  changed |= ImGui::Checkbox("slice plane", &v.slice.enabled);
  if (v.slice.enabled) changed |= drawSliceOptions(v);
  changed |= ImGui::Checkbox("bounds box", &v.showBounds);
  ctx_.recordWidget("view.bounds_box");
  ImGui::SameLine();
  changed |= ImGui::Checkbox("axes", &v.showAxes);
  ctx_.recordWidget("view.axes");
  ImGui::SameLine();
  bool ground = v.ground == Ground::Grid;
  if (ImGui::Checkbox("ground", &ground)) {
    v.ground = ground ? Ground::Grid : Ground::Off;
    changed = true;
  }
  ctx_.recordWidget("view.ground");
  return changed;
}

// The slice normal (an axis) and offset (a slider, one undo step per drag): true when the normal changed.
bool ViewPanel::drawSliceOptions(ViewSpec& v) {
  bool changed = false;
  const char* axes[] = {"x", "y", "z"};
  int axis = v.slice.normal[0] != 0 ? 0 : v.slice.normal[1] != 0 ? 1 : 2;
  if (ImGui::Combo("slice normal", &axis, axes, 3)) {
    v.slice.normal = {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
    changed = true;
  }
  double offset = v.slice.offset;
  const double extent = sliceOffsetExtent(ctx_);  // offsets that cut the bounds
  const double lo = -extent, hi = extent;
  if (ImGui::SliderScalar("slice offset", ImGuiDataType_Double, &offset, &lo, &hi, "%.3f")) {
    if (!ctx_.document.inGesture()) ctx_.document.begin("slice offset");
    v.slice.offset = offset;
    Scene n = ctx_.scene();
    n.view.slice.offset = offset;
    ctx_.document.update(n);
  }
  if (ImGui::IsItemDeactivated() && ctx_.document.inGesture()) ctx_.document.end();
  ImGui::SameLine();
  helpMarker("or Alt + drag in the view: the plane follows the mouse along its normal.");
  return changed;
}

// Fit to view, reset, stored views and screenshots.
void ViewPanel::drawCameraButtons() {
  const Scene& s = ctx_.scene();
  if (ImGui::Button("Fit to view (F)")) camera_.fitToView();
  ImGui::SameLine();
  if (ImGui::Button("Reset (Home)")) camera_.resetView();
  if (s.mode != SceneMode::Implicit2d) {
    if (ImGui::Button("Store view")) {
      savedViews_.push_back(ctx_.scene().view.camera);
      ctx_.setStatus("stored view " + std::to_string(savedViews_.size()));
    }
    for (std::size_t k = 0; k < savedViews_.size(); ++k) {
      ImGui::SameLine();
      if (ImGui::Button(std::to_string(k + 1).c_str()))
        ctx_.document.setCamera(savedViews_[k], ctx_.scene().view.center2d, ctx_.scene().view.halfHeight2d);
    }
  }
  ImGui::Checkbox("screenshot with panels", &ctx_.screenshotWithUi);
  if (ImGui::Button("Screenshot (F12)")) ctx_.requestNumberedScreenshot();
}

}  // namespace hermite::app
