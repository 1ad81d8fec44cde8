// The Transform section: the similarity (translate, rotate, uniform scale) in numeric fields, the
// general matrix (composition), the update / re-solve choice, verification on request, and what
// the shown fit did (method, times, differences). The gizmo (tools/transform_gizmo.h) edits the
// same transform in the view.

#include "app/panels/transform_panel.h"

#include <imgui.h>

#include <cstdio>
#include <string>

#include "app/gui/gui_widgets.h"
#include "scene/scene_fit.h"

namespace hermite::app {
namespace {

// The angle and scale sliders: one undo step per drag, each move an update of the document
// (`s` follows it).
void drawRotateScale(GuiContext& ctx, Scene& s, int dim) {
  double angle = dim == 3 ? s.transform.rotateAxisAngleDeg[3] : s.transform.rotateDeg;
  const double lo = -180, hi = 180;
  if (ImGui::SliderScalar("angle (deg)", ImGuiDataType_Double, &angle, &lo, &hi, "%.2f")) {
    if (!ctx.document.inGesture()) ctx.document.begin("rotate");
    Scene n = ctx.scene();
    if (dim == 3) n.transform.rotateAxisAngleDeg[3] = angle;
    else n.transform.rotateDeg = angle;
    ctx.document.update(n);
    s = ctx.scene();
  }
  if (ImGui::IsItemDeactivated() && ctx.document.inGesture()) ctx.document.end();
  double q = s.transform.scale;
  const double qlo = 0.05, qhi = 20;
  if (ImGui::SliderScalar("scale", ImGuiDataType_Double, &q, &qlo, &qhi, "%.4g", ImGuiSliderFlags_Logarithmic)) {
    if (!ctx.document.inGesture()) ctx.document.begin("scale");
    Scene n = ctx.scene();
    n.transform.scale = q;
    ctx.document.update(n);
    s = ctx.scene();
  }
  if (ImGui::IsItemDeactivated() && ctx.document.inGesture()) ctx.document.end();
}

// What the shown fit did with the transform: the method, times and, when verified, the
// difference from the re-solve.
void drawTransformReport(const GuiContext& ctx) {
  const FitOutcome* f = ctx.fits.shown().get();
  const SceneFitReport* fitted = f ? f->implicitFit() : nullptr;
  if (fitted && fitted->transformed) {
    const TransformReport& r = fitted->transform;
    ImGui::Separator();
    ImGui::Text("shown: %s%s", r.method.c_str(), r.exact ? " (= the re-solve)" : "");
    if (ctx.options.showTimings) ImGui::Text("update %.3f ms", r.updateMs);
    if (r.resolveMs) {
      if (ctx.options.showTimings) ImGui::Text("re-solve %.2f ms", *r.resolveMs);
      ImGui::Text("max |f_update - f_resolve|  %.2e", *r.maxAbsDf);
      ImGui::Text("max |grad difference|       %.2e", *r.maxGradDiff);
    }
    if (r.method == "composition")
      ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "composition f(T^-1 x): not the re-solved interpolant");
  }
}

// Translation, and the rotation axis in 3D (numeric fields, applied on Enter).
bool drawTranslateAxis(TransformSpec& t, int dim, std::string& label) {
  bool changed = false;
  double tr[3] = {0, 0, 0};
  for (int k = 0; k < dim && k < int(t.translate.size()); ++k) tr[k] = t.translate[std::size_t(k)];
  if (ImGui::InputScalarN("translate", ImGuiDataType_Double, tr, dim, nullptr, nullptr, "%.4g",
                          ImGuiInputTextFlags_EnterReturnsTrue)) {
    t.translate.assign(tr, tr + dim);
    changed = true;
    label = "translate";
  }
  if (dim == 3) {
    double axis[3] = {t.rotateAxisAngleDeg[0], t.rotateAxisAngleDeg[1], t.rotateAxisAngleDeg[2]};
    if (ImGui::InputScalarN("rotation axis", ImGuiDataType_Double, axis, 3, nullptr, nullptr, "%.3g",
                            ImGuiInputTextFlags_EnterReturnsTrue) &&
        (axis[0] != 0 || axis[1] != 0 || axis[2] != 0)) {
      t.rotateAxisAngleDeg = {axis[0], axis[1], axis[2], t.rotateAxisAngleDeg[3]};
      changed = true;
      label = "rotation axis";
    }
  }
  return changed;
}

// The model choice (auto, update coefficients, re-solve) and the non-uniform scale, a diagonal
// transform.matrix (the composition f(T⁻¹x)).
bool drawMethodAndMatrix(GuiContext& ctx, TransformSpec& t, int dim, std::string& label) {
  bool changed = false;
  int method = int(t.method);
  ImGui::TextUnformatted("model");
  ImGui::SameLine();
  ImGui::RadioButton("auto", &method, 0);
  ImGui::SameLine();
  ImGui::RadioButton("update coefficients", &method, 1);
  ImGui::SameLine();
  ImGui::RadioButton("re-solve", &method, 2);
  ctx.recordWidget("transform.method");
  if (method != int(t.method)) {
    t.method = TransformMethod(method);
    changed = true;
    label = "transform model";
  }
  double diag[3] = {1, 1, 1};
  if (int(t.matrix.size()) == dim * dim)
    for (int k = 0; k < dim; ++k) diag[k] = t.matrix[std::size_t(k * dim + k)];
  if (ImGui::InputScalarN("non-uniform scale", ImGuiDataType_Double, diag, dim, nullptr, nullptr, "%.3g",
                          ImGuiInputTextFlags_EnterReturnsTrue) &&
      diag[0] > 0 && diag[1] > 0 && (dim == 2 || diag[2] > 0)) {
    t.matrix.assign(std::size_t(dim * dim), 0.0);
    for (int k = 0; k < dim; ++k) t.matrix[std::size_t(k * dim + k)] = diag[k];
    if (t.matrixIsIdentity()) t.matrix.clear();
    changed = true;
    label = "non-uniform scale";
  }
  helpMarker("Not a similarity: the field becomes the composition f(T^-1 x), which is NOT the re-solved "
             "interpolant of the transformed data (the Diagnostics show how far it is from one).");
  return changed;
}

// Verification against a re-solve, and the reset (which keeps the verification choice).
bool drawVerifyReset(TransformSpec& t, int dim, std::string& label) {
  bool changed = false;
  if (ImGui::Checkbox("verify against a re-solve", &t.verify)) {
    changed = true;
    label = t.verify ? "verify the transform" : "stop verifying the transform";
  }
  helpMarker("Also re-solve on the transformed data and compare the shown field with it on probes "
             "(transform.verify). Costs a whole fit per change.");
  if (ImGui::Button("Reset transform")) {
    const bool verify = t.verify;
    t = TransformSpec{};
    t.translate.assign(std::size_t(dim), 0.0);
    t.verify = verify;
    changed = true;
    label = "reset transform";
  }
  return changed;
}

}  // namespace

void drawTransformPanel(GuiContext& ctx) {
  Scene s = ctx.scene();
  const int dim = ctx.dimension();
  std::string label = "transform";
  ImGui::Checkbox("gizmo", &ctx.showGizmo);
  helpMarker("Drag the arrows (translate), the rings (rotate) or the yellow square (uniform scale) in the view.");
  bool changed = drawTranslateAxis(s.transform, dim, label);
  drawRotateScale(ctx, s, dim);
  changed |= drawMethodAndMatrix(ctx, s.transform, dim, label);
  changed |= drawVerifyReset(s.transform, dim, label);
  if (changed) ctx.document.apply(s, label);
  drawTransformReport(ctx);
}

}  // namespace hermite::app
