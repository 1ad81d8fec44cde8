#include "app/ui_panels.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <filesystem>

#include <imgui.h>

#include "core/hermite_samples.h"

namespace hermite::app {

template <int Dim>
FitDiagnostics fitDiagnostics(const Scene& scene, const SceneFit<Dim>& fit) {
  FitDiagnostics d;
  d.sceneName = std::filesystem::path(scene.sourceName).filename().string();  // the full path is too wide
  d.mode = std::string(sceneModeName(scene.mode));
  d.method = std::string(fitMethodName(scene.fit.method));
  d.kernel = std::string(kernelName(scene.fit.kernel));
  d.radius = scene.fit.radius;
  d.radiusUsed = Kernel{scene.fit.kernel, scene.fit.radius}.usesRadius();
  d.polynomial = std::string(polynomialName(scene.fit.polynomial));
  d.smoothing = scene.fit.smoothing;
  d.nSamples = fit.report.nSamples;
  d.nUnknowns = fit.report.nUnknowns;
  d.solver = fit.report.solver;
  d.conditionEstimate = fit.report.conditionEstimate;
  d.fitMs = fit.report.fitMs;
  d.meanSpacing = meanSampleSpacing<Dim>(fit.samples.points);
  d.warnings = fit.warnings;
  if (fit.transformed) d.transform = fit.transform.method;
  const FitResiduals r = fitResiduals(fit);
  d.maxAbsF = r.maxAbsF;
  d.maxGradError = r.maxGradError;
  return d;
}

template FitDiagnostics fitDiagnostics<2>(const Scene&, const SceneFit<2>&);
template FitDiagnostics fitDiagnostics<3>(const Scene&, const SceneFit<3>&);

namespace {

void row(const char* name, const char* fmt, ...) IM_FMTARGS(2);
void row(const char* name, const char* fmt, ...) {
  ImGui::TextDisabled("%s", name);
  ImGui::SameLine(110.0f);
  va_list args;
  va_start(args, fmt);
  ImGui::TextV(fmt, args);
  va_end(args);
}

// Residuals at rounding-noise level differ in their digits between CPUs (vectorisation, BLAS
// kernels); below 1e-10 only the bound is shown, so headless screenshots agree across machines.
std::string residualText(double v) {
  if (v < 1e-10) return "< 1e-10";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  return buf;
}

}  // namespace

void drawInfoPanel(const FitDiagnostics& d) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(std::max(60.0f, display.x - 16),
                                                           std::max(40.0f, display.y - 16)));
  ImGui::SetNextWindowBgAlpha(0.92f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  if (ImGui::Begin("Hermite Lab", nullptr, flags)) {
    ImGui::Text("%s", d.sceneName.c_str());
    ImGui::Separator();
    row("mode", "%s", d.mode.c_str());
    row("method", "%s", d.method.c_str());
    if (d.radiusUsed) {
      row("kernel", "%s  r = %.4g", d.kernel.c_str(), d.radius);
      if (d.meanSpacing > 0) row("r / spacing", "%.3g", d.radius / d.meanSpacing);
    } else {
      row("kernel", "%s (no radius)", d.kernel.c_str());
    }
    row("polynomial", "%s", d.polynomial.c_str());
    if (d.smoothing > 0) row("smoothing", "%.3g", d.smoothing);
    row("samples", "%d  (%d unknowns)", d.nSamples, d.nUnknowns);
    row("solver", "%s", d.solver.c_str());
    row("condition", "%.3g", d.conditionEstimate);
    row("max |f(p)|", "%s", residualText(d.maxAbsF).c_str());
    row("max |grad-n|", "%s", residualText(d.maxGradError).c_str());
    if (d.showTimings) row("fit", "%.2f ms", d.fitMs);
    if (!d.transform.empty()) row("transform", "%s", d.transform.c_str());
    for (const auto& [name, value] : d.viewLines) row(name.c_str(), "%s", value.c_str());
    if (!d.warnings.empty()) {
      ImGui::Separator();
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 300.0f);
      for (const std::string& w : d.warnings) ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %s", w.c_str());
      ImGui::PopTextWrapPos();
    } else {
      row("warnings", "none");
    }
  }
  ImGui::End();
}

void drawAppPanels(const FitDiagnostics& diagnostics) { drawInfoPanel(diagnostics); }

}  // namespace hermite::app
