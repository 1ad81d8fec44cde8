#include "app/panels/diagnostics_panel.h"

#include <imgui.h>

#include <cstdarg>
#include <cstdio>

#include "app/gui/clipped_text.h"
#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

// One row of the two-column table: the label left, the value (printf format) right. Columns of
// a table line up whatever the font's glyph widths (spaces in a proportional font do not).
__attribute__((format(printf, 2, 3))) void row(const char* label, const char* format, ...) {
  char value[256];
  va_list args;
  va_start(args, format);
  std::vsnprintf(value, sizeof value, format, args);
  va_end(args);
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextUnformatted(label);
  ImGui::TableSetColumnIndex(1);
  ImGui::TextUnformatted(value);
}

bool beginRows() {
  return ImGui::BeginTable("diagnostics", 2, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_NoSavedSettings);
}

void holeFillRows(const GuiContext& ctx, const HoleFillStages& holefill) {
  if (!beginRows()) return;
  row("stage", "%s", std::string(holeFillStageName(ctx.scene().holefill.stage)).c_str());
  row("holes", "%d", int(holefill.holes.size()));
  row("added", "%d triangles", holefill.trianglesAdded);
  ImGui::EndTable();
}

void patchRows(GuiContext& ctx, const PatchDisplay& v) {
  if (!beginRows()) return;
  row("patches", "%d x %d", v.grid.patchesU(), v.grid.patchesV());
  row("form", "%s", std::string(patchFormName(ctx.scene().patch.form)).c_str());
  if (!v.vertexError.empty()) row("max error", "%.3g", v.maxError);
  if (ctx.options.showTimings) row("tessellate", "%.2f ms, view %.0f ms", v.tessellateMs, ctx.image.result().ms);
  ImGui::EndTable();
}

// Solver, size, condition, residuals and the view's trace mode of an implicit fit.
void implicitFitRows(GuiContext& ctx, const FitOutcome& f, const FitReport& r) {
  if (!beginRows()) return;
  const FitResiduals& res = f.residuals();  // computed by the fit worker
  row("solver", "%s", r.solver.c_str());
  row("unknowns", "%d (%d samples)", r.nUnknowns, r.nSamples);
  if (ctx.options.showTimings) row("fit", "%.2f ms", r.fitMs);
  row("condition", "%.3g", r.conditionEstimate);
  // Residuals at rounding-noise level differ in their digits between CPUs: below 1e-10 only the
  // bound is shown, so headless screenshots agree across machines.
  const auto residual = [](const char* label, double v) {
    if (v < 1e-10) row(label, "< 1e-10");
    else row(label, "%.2e", v);
  };
  residual("max |f(p)|", res.maxAbsF);
  residual("max |grad f - n|", res.maxGradError);
  const std::string& mode = ctx.image.result().traceMode;
  if (ctx.options.showTimings) {
    if (!mode.empty()) row("view", "%s, %.0f ms", mode.c_str(), ctx.image.result().ms);
    else row("view", "%.0f ms", ctx.image.result().ms);
  } else if (!mode.empty()) {
    row("view", "%s", mode.c_str());
  }
  ImGui::EndTable();
}

}  // namespace

void drawDiagnosticsPanel(GuiContext& ctx) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.90f);
  if (ImGui::Begin("Diagnostics", nullptr,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                       ImGuiWindowFlags_NoFocusOnAppearing)) {
    const FitOutcome* f = ctx.fits.shown().get();
    if (!f) {
      ImGui::TextDisabled(ctx.fits.lastError().empty() ? "fitting..." : "no model");
    } else if (const auto* holefill = f->as<HoleFillStages>()) {
      holeFillRows(ctx, *holefill);
    } else if (const auto* patch = f->as<PatchDisplay>()) {
      patchRows(ctx, *patch);
    } else if (const SceneFitReport* fitted = f->implicitFit()) {
      implicitFitRows(ctx, *f, fitted->report);
      if (ctx.fits.shownVersion() != ctx.document.version()) ImGui::TextDisabled("(showing an earlier version)");
      // Each warning in at most two lines; a longer one shows in full while hovered (and in
      // the message log), so the panel keeps its size.
      for (const std::string& w : f->warnings())
        clippedText("! " + w, ctx.px(300.0f), 2, ImVec4(1.0f, 0.75f, 0.2f, 1.0f));
    }
    if (ctx.fits.worker().busy()) {
      char text[64];
      std::snprintf(text, sizeof text, "fitting %.1f s", ctx.fits.worker().runningMs() / 1000.0);
      ImGui::ProgressBar(float(ctx.fits.worker().progress()), ImVec2(ctx.px(200.0f), 0), text);
      ImGui::SameLine();
      const bool cancelled = ImGui::Button("Cancel");
      ctx.recordWidget("diagnostics.cancel");
      if (cancelled) {
        ctx.fits.cancel(ctx.document.version());
        ctx.setStatus("fit cancelled; showing the previous result");
      }
    }
  }
  ImGui::End();
}

}  // namespace hermite::app
