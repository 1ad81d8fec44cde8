#include "app/panels/message_log.h"

#include <imgui.h>

#include <ctime>

namespace hermite::app {

namespace {

const char* severityName(Severity s) {
  switch (s) {
    case Severity::Info: return "info";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "";
}

ImVec4 severityColour(Severity s) {
  switch (s) {
    case Severity::Info: return ImGui::GetStyleColorVec4(ImGuiCol_Text);
    case Severity::Warning: return ImVec4(1.0f, 0.75f, 0.2f, 1.0f);
    case Severity::Error: return ImVec4(1.0f, 0.45f, 0.4f, 1.0f);
  }
  return ImVec4(1, 1, 1, 1);
}

// "HH:MM:SS" in local time.
std::string timeOfDay(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm local{};
  localtime_r(&seconds, &local);
  char text[16];
  std::strftime(text, sizeof text, "%H:%M:%S", &local);
  return text;
}

}  // namespace

void drawMessageLog(GuiContext& ctx) {
  const ImGuiIO& io = ImGui::GetIO();
  const float font = ImGui::GetFontSize();
  ImGui::SetNextWindowSize(ImVec2(font * 46, font * 20), ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.95f);
  if (ImGui::Begin("Messages", &ctx.panels.messages, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::Text("%zu messages", ctx.status.log.size());
    ImGui::SameLine();
    if (ImGui::SmallButton("Clear")) ctx.status.log.clear();
    ctx.recordWidget("messages.clear");
    ImGui::Separator();
    ImGui::BeginChild("##log");
    const bool atBottom = ImGui::GetScrollY() >= ImGui::GetScrollMaxY();
    for (const LogEntry& e : ctx.status.log) {
      ImGui::TextDisabled("%s %-7s", timeOfDay(e.time).c_str(), severityName(e.severity));
      ImGui::SameLine();
      ImGui::PushStyleColor(ImGuiCol_Text, severityColour(e.severity));
      ImGui::TextWrapped("%s", e.text.c_str());
      ImGui::PopStyleColor();
    }
    if (atBottom) ImGui::SetScrollHereY(1.0f);  // follow new messages unless scrolled back
    ImGui::EndChild();
  }
  ImGui::End();
}

}  // namespace hermite::app
