// The patch editor: the Patch panel (preset, splits, domain, form switch, display,
// the torus error table) and the handles in the view — drawn with ImGui over the rasterised
// grid, grabbed with the mouse and dragged on the plane through the handle facing the camera;
// holding X, Y or Z constrains the drag to that axis. Every edit is an edit of the knot data in
// the scene (scene/patch_document.h), so undo, save and `render` see it.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>

#include "app/panels/patch_editor.h"
#include "app/gui/gui_widgets.h"

namespace hermite::app {

namespace {

constexpr double kHandlePickPx = 8.0;

ImU32 handleColour(const PatchHandle& h) {
  switch (h.kind) {
    case PatchHandle::Point: return IM_COL32(30, 30, 30, 255);
    case PatchHandle::TangentU: return IM_COL32(215, 40, 25, 255);
    case PatchHandle::TangentV: return IM_COL32(25, 150, 40, 255);
    case PatchHandle::Twist: return IM_COL32(40, 75, 230, 255);
    case PatchHandle::Control: return IM_COL32(115, 50, 155, 255);
  }
  return IM_COL32(0, 0, 0, 255);
}

const char* handleName(const PatchHandle& h) {
  switch (h.kind) {
    case PatchHandle::Point: return "point";
    case PatchHandle::TangentU: return "u-tangent";
    case PatchHandle::TangentV: return "v-tangent";
    case PatchHandle::Twist: return "twist";
    case PatchHandle::Control: return "control point";
  }
  return "handle";
}

}  // namespace

std::optional<Vec<2>> PatchEditor::handlePosition(const PatchHandle& h) const {
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  const Vec<3> p = patchHandlePosition(ctx_.scene().patch, patchKnotData(ctx_.scene().patch), h);
  return cam.projectVisible(p);
}

bool PatchEditor::press(const Vec<2>& mouse) {
  if (!ctx_.scene().patch.showHandles) return false;
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  double best = kHandlePickPx;
  std::optional<std::pair<PatchHandle, Vec<3>>> hit;
  for (const auto& [h, p] : patchHandles(ctx_.scene().patch)) {
    const std::optional<Vec<2>> at = cam.projectVisible(p);
    if (!at) continue;
    const double d = (*at - mouse).norm();
    // Ties (shared corners, coincident tips): the first in the list wins — points before tips.
    if (d < best) {
      best = d;
      hit = std::pair{h, p};
    }
  }
  if (!hit) return false;
  grabbed_ = hit->first;
  grabStart_ = hit->second;
  ctx_.document.begin(std::string("move ") + handleName(grabbed_));
  ctx_.setStatus(std::string("moving the ") + handleName(grabbed_) + " (hold X, Y or Z to constrain)");
  return true;
}

void PatchEditor::drag(const Vec<2>& mouse, const FrameInput& in) {
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  const Ray ray = cam.ray(mouse.x(), mouse.y());
  const double denom = ray.direction.dot(cam.forward());
  if (std::abs(denom) < 1e-12) return;
  const double t = (grabStart_ - ray.origin).dot(cam.forward()) / denom;
  if (!(t > 0)) return;
  Vec<3> target = ray.at(t);
  // Axis constraint: the closest point of the axis line through the grab point to the ray.
  for (int axis = 0; axis < 3; ++axis) {
    if (!in.keysDown[GLFW_KEY_X + axis]) continue;
    const Vec<3> e = Vec<3>::Unit(axis);
    const Vec<3> w = grabStart_ - ray.origin;
    const double b = e.dot(ray.direction), d = e.dot(w), f = ray.direction.dot(w);
    const double den = 1 - b * b;
    if (den < 1e-9) break;  // the axis points at the eye: no motion along it is visible
    const double s = (b * f - d) / den;
    target = grabStart_ + s * e;
    break;
  }
  Scene s = ctx_.scene();
  s.patch = movePatchHandle(s.patch, grabbed_, target);
  ctx_.document.update(s);
}

void PatchEditor::drawHandles() const {
  const PatchSpec& spec = ctx_.scene().patch;
  if (!spec.showHandles || ctx_.scene().mode != SceneMode::Patch) return;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  const Vec<2> o = ctx_.view.origin();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (const auto& [h, p] : patchHandles(spec)) {
    const std::optional<Vec<2>> shown = cam.projectVisible(p);
    if (!shown) continue;
    const Vec<2> q = *shown + o;
    const ImVec2 at(float(q.x()), float(q.y()));
    const bool grabbed = ctx_.drag == Drag::PatchHandle && h.kind == grabbed_.kind && h.a == grabbed_.a &&
                         h.b == grabbed_.b && h.p == grabbed_.p && h.q == grabbed_.q;
    const bool hover = std::hypot(mouse.x - at.x, mouse.y - at.y) < kHandlePickPx;
    const float r = h.kind == PatchHandle::Point ? 5.0f : 4.0f;
    dl->AddCircleFilled(at, r + (hover || grabbed ? 2.0f : 0.0f), handleColour(h));
    dl->AddCircle(at, r + (hover || grabbed ? 2.0f : 0.0f), IM_COL32(255, 255, 255, 200), 12, 1.2f);
  }
}

namespace {

// The patch's data: preset, splits and domain. Each change clears the edited knots (the data
// come from the preset again); `label` names the change for undo.
bool drawPatchData(PatchSpec& p, std::string& label) {
  bool changed = false;
  if (ImGui::BeginCombo("preset##patch", p.preset.c_str())) {
    for (const auto& [name, description] : patchPresets()) {
      if (ImGui::Selectable(name.c_str(), name == p.preset) && name != p.preset) {
        p.preset = name;
        p.knots.clear();  // a preset replaces the edited data
        changed = true;
        label = "preset " + name;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", description.c_str());
    }
    ImGui::EndCombo();
  }
  int splits[2] = {p.splits[0], p.splits[1]};
  if (ImGui::InputInt2("splits n x m", splits, ImGuiInputTextFlags_EnterReturnsTrue)) {
    splits[0] = std::clamp(splits[0], 1, 16);
    splits[1] = std::clamp(splits[1], 1, 16);
    if (splits[0] != p.splits[0] || splits[1] != p.splits[1]) {
      p.splits = {splits[0], splits[1]};
      p.knots.clear();  // new knots: the data come from the preset again
      changed = true;
      label = "splits";
    }
  }
  double domain[4] = {p.domain[0], p.domain[1], p.domain[2], p.domain[3]};
  if (ImGui::InputScalarN("domain u0 u1 v0 v1", ImGuiDataType_Double, domain, 4, nullptr, nullptr, "%.3g",
                          ImGuiInputTextFlags_EnterReturnsTrue) &&
      domain[0] < domain[1] && domain[2] < domain[3]) {
    p.domain = {domain[0], domain[1], domain[2], domain[3]};
    p.knots.clear();
    changed = true;
    label = "domain";
  }
  return changed;
}

// How the patch is shown and edited: Hermite or Bézier handles, colouring, tessellation, and
// the reset of edited knots.
bool drawPatchDisplay(GuiContext& ctx, PatchSpec& p, std::string& label) {
  bool changed = false;
  int form = p.form == PatchForm::Hermite ? 0 : 1;
  ImGui::RadioButton("Hermite", &form, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Bezier", &form, 1);
  if ((form == 1) != (p.form == PatchForm::Bezier)) {
    p.form = form == 1 ? PatchForm::Bezier : PatchForm::Hermite;  // the surface does not change
    changed = true;
    label = "form";
  }
  ctx.recordWidget("patch.form");
  helpMarker("Hermite: corner points, u/v tangents (red/green) and twists (blue) per knot. Bezier: the 16 "
              "control points per patch. Both edit the same knot data, so the surface never jumps when you switch.");
  changed |= ImGui::Checkbox("error colour", &p.showError);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("iso-lines", &p.showIsoLines);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("handles", &p.showHandles);
  int tess = p.tessellation;
  if (ImGui::SliderInt("samples / patch", &tess, 2, 128)) {
    p.tessellation = tess;
    changed = true;
  }
  if (!p.knots.empty() && ImGui::Button("Reset to the preset")) {
    p.knots.clear();
    changed = true;
    label = "reset patch";
  }
  return changed;
}

// The shown patch grid's size and timing, its largest error against the torus, and the torus
// error table by splits.
void drawPatchSummary(const FitOutcome& f, const PatchDisplay& v, bool showTimings) {
  ImGui::Separator();
  ImGui::Text("%d x %d patches, %d triangles", v.grid.patchesU(), v.grid.patchesV(), int(v.mesh.triangles.cols()));
  if (showTimings) ImGui::Text("tessellation %.2f ms", v.tessellateMs);
  if (!v.vertexError.empty()) ImGui::Text("max |X - torus| %.3g", v.maxError);
  if (!v.table.empty() && ImGui::BeginTable("torus error", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("splits");
    ImGui::TableSetupColumn("err x");
    ImGui::TableSetupColumn("err y");
    ImGui::TableSetupColumn("err z");
    ImGui::TableHeadersRow();
    for (const PatchStudyRow& r : v.table) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%dx%d", r.splits[0], r.splits[1]);
      for (double e : r.error) {
        ImGui::TableNextColumn();
        ImGui::Text("%.3g", e);
      }
    }
    ImGui::EndTable();
  } else if (f.scene.patch.preset == "torus" && !f.scene.patch.knots.empty()) {
    ImGui::TextDisabled("(error table: the data are edited, not the torus's)");
  }
}

}  // namespace

void PatchEditor::drawPanel() {
  Scene s = ctx_.scene();
  std::string label = "patch";
  bool changed = drawPatchData(s.patch, label);
  changed |= drawPatchDisplay(ctx_, s.patch, label);
  if (changed) ctx_.document.apply(s, label);
  const FitOutcome* f = ctx_.fits.shown().get();
  if (const PatchDisplay* shownPatch = f ? f->as<PatchDisplay>() : nullptr)
    drawPatchSummary(*f, *shownPatch, ctx_.options.showTimings);
}

}  // namespace hermite::app
