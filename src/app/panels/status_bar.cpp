#include "app/panels/status_bar.h"

#include <imgui.h>

#include <algorithm>

#include "app/gui/clipped_text.h"

namespace hermite::app {

void drawStatusBar(GuiContext& ctx) {
  const ImGuiIO& io = ImGui::GetIO();
  const float height = ctx.px(kStatusBarHeight), pathWidth = ctx.px(kLeftPanelWidth);
  ImGui::SetNextWindowPos(ImVec2(0, io.DisplaySize.y - height), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, height), ImGuiCond_Always);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(ctx.px(8), ctx.px(3)));
  ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(ctx.px(8), ctx.px(1)));
  if (ImGui::Begin("##status", nullptr,
                   ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                       ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus)) {
    const std::string file = (ctx.document.path().empty() ? "(unsaved scene)" : ctx.document.path()) +
                             (ctx.document.dirty() ? " *" : "");
    const float gap = ImGui::GetStyle().ItemSpacing.x;
    clippedText(file, pathWidth - 2 * gap, 2, ImGui::GetStyleColorVec4(ImGuiCol_Text));
    ctx.recordWidget("status.path");
    ImGui::SameLine(pathWidth);
    const float logWidth = ImGui::CalcTextSize("log").x + 2 * ImGui::GetStyle().FramePadding.x;
    const float messageWidth = std::max(ctx.px(40), io.DisplaySize.x - pathWidth - logWidth - 3 * gap);
    const ImVec4 colour = ctx.status.error ? ImVec4(1, 0.45f, 0.4f, 1) : ImGui::GetStyleColorVec4(ImGuiCol_Text);
    clippedText(ctx.status.message, messageWidth, 2, colour);
    ctx.recordWidget("status.message");
    ImGui::SameLine(io.DisplaySize.x - logWidth - gap);
    if (ImGui::SmallButton("log")) ctx.panels.messages = !ctx.panels.messages;
    ctx.recordWidget("status.log");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("every message in full, with its time (F2)");
  }
  ImGui::End();
  ImGui::PopStyleVar(2);
}

}  // namespace hermite::app
