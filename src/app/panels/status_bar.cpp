#include "app/panels/status_bar.h"

#include <imgui.h>

namespace hermite::app {

void drawStatusBar(const GuiContext& ctx) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, io.DisplaySize.y - kStatusBarHeight), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, kStatusBarHeight), ImGuiCond_Always);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  if (ImGui::Begin("##status", nullptr,
                   ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                       ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus)) {
    const std::string file = ctx.document.path().empty() ? "(unsaved scene)" : ctx.document.path();
    ImGui::Text("%s%s", file.c_str(), ctx.document.dirty() ? " *" : "");
    ImGui::SameLine(320);
    if (ctx.status.error) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", ctx.status.message.c_str());
    else ImGui::TextUnformatted(ctx.status.message.c_str());
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

}  // namespace hermite::app
