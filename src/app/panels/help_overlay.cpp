#include "app/panels/help_overlay.h"

#include <imgui.h>

namespace hermite::app {

void drawHelpOverlay(GuiContext& ctx) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.95f);
  if (ImGui::Begin("Controls", &ctx.panels.help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    const char* rows[][2] = {
        {"left drag (3D)", "orbit (2D: pan), unless it starts on the selection"},
        {"right / middle drag, Shift+left", "pan"},
        {"wheel", "zoom towards the cursor"},
        {"arrows over the r slider", "r \xC3\x97 or \xC3\xB7 1.05 (Shift: 1.005)"},
        {"F / Home", "fit to view / reset the camera"},
        {"click a sample", "select it (highlighted)"},
        {"drag the selected sample", "move it (3D: on the plane facing the camera)"},
        {"Ctrl+Shift+drag", "move any sample"},
        {"drag the normal's tip", "rotate the normal"},
        {"N / Del", "flip the normal / delete the sample"},
        {"Ctrl+click", "add a sample (3D: on the surface or the slice plane)"},
        {"Alt+drag", "move the slice plane along its normal (3D, slice on)"},
        {"Ctrl+Z / Ctrl+Shift+Z", "undo / redo (every edit, fit settings too)"},
        {"Ctrl+S", "save the scene"},
        {"Tab", "hide / show the panels"},
        {"F12", "screenshot (numbered PNG)"},
        {"Ctrl + / Ctrl \xE2\x88\x92 / Ctrl 0", "larger / smaller type and panels / back to the start scale"},
        {"F5", "presenter mode: panels hidden, a large caption"},
        {"F2", "the message log: every message in full"},
        {"E", "r explorer (plots against r, thumbnails)"},
        {"F1 or ?", "this help"},
    };
    for (const auto& r : rows) {
      ImGui::TextUnformatted(r[0]);
      ImGui::SameLine(ctx.px(250));
      ImGui::TextDisabled("%s", r[1]);
    }
  }
  ImGui::End();
}

}  // namespace hermite::app
