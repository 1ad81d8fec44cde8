#pragma once
// Small ImGui helpers the panels share (inline: header only).

#include <imgui.h>

#include <cstdio>
#include <string>
#include <string_view>

namespace hermite::app {

inline std::string toString(std::string_view v) { return std::string(v); }

// A combo over `items` (an array or container of T) showing names; returns true when the
// choice changed.
template <class T, class Items, class NameOf>
inline bool comboOf(const char* label, T& value, const Items& items, NameOf nameOf) {
  bool changed = false;
  if (ImGui::BeginCombo(label, toString(nameOf(value)).c_str())) {
    for (const T& item : items) {
      const bool selected = item == value;
      if (ImGui::Selectable(toString(nameOf(item)).c_str(), selected) && !selected) {
        value = item;
        changed = true;
      }
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  return changed;
}

inline bool inputText(const char* label, std::string& text) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%s", text.c_str());
  const bool changed = ImGui::InputText(label, buf, sizeof buf);
  if (changed) text = buf;
  return changed;
}

inline void helpMarker(const char* text) {
  ImGui::SameLine();
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

}  // namespace hermite::app
