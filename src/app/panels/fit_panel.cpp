#include "app/panels/fit_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

const Polynomial kPolys[] = {Polynomial::None, Polynomial::Linear, Polynomial::Quadratic};

// The choices of an AutoSwitch key, in its order.
const char* const kSwitchNames[] = {"auto", "on", "off"};

// r's factor per pixel of a Shift+drag on the r slider.
constexpr double kFineStepPerPixel = 1.002;

// The arrow keys over the r slider nudge r by 5 % (with Shift by 0.5 %), one undo step each.
void nudgeRadius(GuiContext& ctx, const FitSpec& fit) {
  if (!ImGui::IsItemHovered() || ctx.document.inGesture()) return;
  const int steps = int(ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow))) -
                    int(ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow)));
  if (steps == 0) return;
  const double factor = ImGui::GetIO().KeyShift ? 1.005 : 1.05;
  FitSpec f = fit;
  f.radius = fit.radius * std::pow(factor, steps);
  editFit(ctx, f, "radius");
}

// r: a logarithmic slider (one undo step per drag; Shift+drag for fine steps) over 0.1 to 200
// mean sample spacings (widened to hold the current r; 1e-4 to 100 before the first fit), exact
// entry, and r in spacings;
// disabled for scale-free kernels. A 50-pixel drag changes r by a factor of about 7, not 40.
void drawRadius(GuiContext& ctx, const FitSpec& fit) {
  const Kernel kernel{fit.kernel, fit.radius};
  const double spacing = ctx.fits.shown() ? ctx.fits.shown()->sampleSpacing() : 0.0;
  ImGui::BeginDisabled(!kernel.usesRadius());
  double r = fit.radius;
  const double rMin = spacing > 0 ? std::min(0.1 * spacing, r) : 1e-4;
  const double rMax = spacing > 0 ? std::max(200.0 * spacing, r) : 100.0;
  bool changed = ImGui::SliderScalar("r", ImGuiDataType_Double, &r, &rMin, &rMax, "%.4g", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemActive() && ImGui::GetIO().KeyShift) {
    // Shift while dragging: fine steps of 0.2 % per pixel from the current r, whatever the
    // slider's own mapping of the mouse position says.
    r = fit.radius * std::pow(kFineStepPerPixel, double(ImGui::GetIO().MouseDelta.x));
    changed = r != fit.radius;
  }
  if (changed) {
    if (!ctx.document.inGesture()) ctx.document.begin("radius");
    Scene s = ctx.scene();
    s.fit.radius = std::clamp(r, rMin, rMax);
    ctx.document.update(s);
  }
  ctx.recordWidget("fit.radius");
  if (ImGui::IsItemDeactivated() && ctx.document.inGesture()) ctx.document.end();  // one undo step per drag
  nudgeRadius(ctx, fit);
  double typed = fit.radius;
  if (ImGui::InputDouble("r exact", &typed, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue) && typed > 0 &&
      std::isfinite(typed)) {
    FitSpec f = fit;
    f.radius = typed;
    editFit(ctx, f, "radius");
  }
  if (spacing > 0 && kernel.usesRadius()) ImGui::Text("r = %.3g \xC3\x97 mean spacing (%.3g)", fit.radius / spacing, spacing);
  ImGui::EndDisabled();
  if (!kernel.usesRadius()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s has no radius (scale-free): r is ignored", toString(kernelName(fit.kernel)).c_str());
    ImGui::PopStyleColor();
  }
}

// The partition-of-unity settings (fit.partition).
void drawPartition(GuiContext& ctx, FitSpec fit) {
  ImGui::Separator();
  ImGui::TextDisabled("partition of unity");
  // fit.partition.enabled: "auto" chooses by size (dense up to 10 000 unknowns), on, off.
  int choice = static_cast<int>(fit.partition.enabled);
  if (ImGui::Combo("enabled", &choice, kSwitchNames, 3)) {
    fit.partition.enabled = static_cast<PartitionSwitch>(choice);
    editFit(ctx, fit, std::string("partition ") + kSwitchNames[choice]);
    fit = ctx.scene().fit;
  }
  ImGui::BeginDisabled(fit.partition.enabled == PartitionSwitch::Off);
  int maxPoints = fit.partition.maxPointsPerBox;
  if (ImGui::InputInt("max points / box", &maxPoints, 1, 10, ImGuiInputTextFlags_EnterReturnsTrue) && maxPoints >= 1) {
    fit.partition.maxPointsPerBox = maxPoints;
    editFit(ctx, fit, "max points per box");
    fit = ctx.scene().fit;
  }
  double box = fit.partition.boxSize;
  if (ImGui::InputDouble("box size", &box, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && box >= 0) {
    fit.partition.boxSize = box;
    editFit(ctx, fit, "box size");
    fit = ctx.scene().fit;
  }
  double overlap = fit.partition.overlap;
  if (ImGui::InputDouble("overlap", &overlap, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) && overlap >= 1) {
    fit.partition.overlap = overlap;
    editFit(ctx, fit, "overlap");
  }
  ImGui::EndDisabled();
}

// Where the field has data: fit.partition.data_reach (both fits) and fit.reach_mask (global fits).
void drawDataReach(GuiContext& ctx, FitSpec fit) {
  ImGui::Separator();
  ImGui::TextDisabled("data reach");
  double reach = fit.partition.dataReach;
  if (ImGui::InputDouble("reach", &reach, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) && reach > 0 &&
      std::isfinite(reach)) {
    fit.partition.dataReach = reach;
    editFit(ctx, fit, "data reach");
    fit = ctx.scene().fit;
  }
  helpMarker("The field has data within this many local sample spacings of a sample: no surface is shown or "
             "exported beyond (fit.partition.data_reach).");
  int choice = static_cast<int>(fit.reachMask);
  if (ImGui::Combo("global fit", &choice, kSwitchNames, 3)) {
    fit.reachMask = static_cast<AutoSwitch>(choice);
    editFit(ctx, fit, std::string("reach mask ") + kSwitchNames[choice]);
  }
  ctx.recordWidget("fit.reach_mask");
  helpMarker("Whether a global fit ends at the data reach too (fit.reach_mask). auto: for data files of at least "
             "50 samples; off shows the whole zero set of the interpolant.");
}

}  // namespace

void drawFitPanel(GuiContext& ctx) {
  FitSpec fit = ctx.scene().fit;
  const FitMethod methods[] = {FitMethod::Hrbf, FitMethod::RbfOffset};
  if (comboOf("method", fit.method, methods, fitMethodName)) editFit(ctx, fit, "method");
  if (comboOf("kernel", fit.kernel, allKernelTypes(), kernelName)) editFit(ctx, fit, "kernel");
  ctx.recordWidget("fit.kernel");
  drawRadius(ctx, fit);

  if (comboOf("polynomial", fit.polynomial, kPolys, polynomialName)) editFit(ctx, fit, "polynomial");
  double lambda = fit.smoothing;
  if (ImGui::InputDouble("smoothing", &lambda, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) && lambda >= 0) {
    fit.smoothing = lambda;
    editFit(ctx, fit, "smoothing");
    fit = ctx.scene().fit;
  }
  helpMarker("lambda >= 0: approximation instead of interpolation (0 interpolates).");
  if (fit.method == FitMethod::RbfOffset) {
    double shift = fit.shift;
    if (ImGui::InputDouble("shift", &shift, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && shift > 0) {
      fit.shift = shift;
      editFit(ctx, fit, "shift");
      fit = ctx.scene().fit;
    }
  }
  drawPartition(ctx, fit);
  drawDataReach(ctx, ctx.scene().fit);
  if (!ctx.fits.lastError().empty()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(ImVec4(1, 0.4f, 0.35f, 1), "last fit failed: %s", ctx.fits.lastError().c_str());
    ImGui::PopTextWrapPos();
  }
}

}  // namespace hermite::app
