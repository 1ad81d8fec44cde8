#include "app/panels/diagnostics_panel.h"

#include <imgui.h>

#include <cstdio>

#include "app/gui/clipped_text.h"
#include "scene/scene_fit.h"

namespace hermite::app {

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
      ImGui::Text("stage       %s", std::string(holeFillStageName(ctx.scene().holefill.stage)).c_str());
      ImGui::Text("holes       %d", int(holefill->holes.size()));
      ImGui::Text("added       %d triangles", holefill->trianglesAdded);
    } else if (const auto* patch = f->as<PatchDisplay>()) {
      const PatchDisplay& v = *patch;
      ImGui::Text("patches     %d x %d", v.grid.patchesU(), v.grid.patchesV());
      ImGui::Text("form        %s", std::string(patchFormName(ctx.scene().patch.form)).c_str());
      if (!v.vertexError.empty()) ImGui::Text("max error   %.3g", v.maxError);
      if (ctx.options.showTimings) ImGui::Text("tessellate  %.2f ms, view %.0f ms", v.tessellateMs, ctx.image.result().ms);
    } else if (const SceneFitReport* fitted = f->implicitFit()) {
      const FitReport& r = fitted->report;
      FitResiduals res;
      f->visitImplicit([&](const auto& fit) { res = fitResiduals(fit); });
      ImGui::Text("solver      %s", r.solver.c_str());
      ImGui::Text("unknowns    %d (%d samples)", r.nUnknowns, r.nSamples);
      if (ctx.options.showTimings) ImGui::Text("fit         %.2f ms", r.fitMs);
      ImGui::Text("condition   %.3g", r.conditionEstimate);
      // Residuals at rounding-noise level differ in their digits between CPUs: below 1e-10
      // only the bound is shown, so headless screenshots agree across machines.
      const auto residual = [](const char* label, double v) {
        if (v < 1e-10) ImGui::Text("%s < 1e-10", label);
        else ImGui::Text("%s %.2e", label, v);
      };
      residual("max |f(p)| ", res.maxAbsF);
      residual("max |grad-n|", res.maxGradError);
      if (ctx.options.showTimings) {
        if (!ctx.image.result().traceMode.empty()) ImGui::Text("view        %s, %.0f ms", ctx.image.result().traceMode.c_str(), ctx.image.result().ms);
        else ImGui::Text("view        %.0f ms", ctx.image.result().ms);
      } else if (!ctx.image.result().traceMode.empty()) {
        ImGui::Text("view        %s", ctx.image.result().traceMode.c_str());
      }
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
