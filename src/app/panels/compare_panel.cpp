#include "app/panels/compare_panel.h"

#include <imgui.h>

#include "app/gui/gui_widgets.h"

namespace hermite::app {

void drawComparePanel(GuiContext& ctx) {
  ImGui::Checkbox("split view", &ctx.compare.enabled);
  helpMarker("The right half shows the same data fitted another way, with the same camera.");
  const char* withNames[] = {"RBF with offset points", "HRBF", "another kernel", "another radius"};
  int with = int(ctx.compare.with);
  if (ImGui::Combo("right half", &with, withNames, 4)) ctx.compare.with = CompareWith(with);
  if (ctx.compare.with == CompareWith::OtherKernel) comboOf("kernel##compare", ctx.compare.kernel, allKernelTypes(), kernelName);
  if (ctx.compare.with == CompareWith::OtherRadius) {
    double r = ctx.compare.radius;
    if (ImGui::InputDouble("r##compare", &r, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && r > 0) ctx.compare.radius = r;
  }
  if (const SceneFitReport* right = ctx.compare.enabled && ctx.fits.shownCompare() ? ctx.fits.shownCompare()->implicitFit() : nullptr) {
    const auto& w = right->warnings;
    ImGui::Text("right: %s", right->report.solver.c_str());
    for (const std::string& m : w) ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %s", m.c_str());
  }
}

}  // namespace hermite::app
