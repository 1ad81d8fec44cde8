#include "app/gui/clipped_text.h"

#include <algorithm>

namespace hermite::app {

namespace {

constexpr const char* kEllipsis = "\xE2\x80\xA6";  // …

// Removes the last UTF-8 code point of `s` (never leaves half a character).
void popCodePoint(std::string& s) {
  while (!s.empty()) {
    const unsigned char c = static_cast<unsigned char>(s.back());
    s.pop_back();
    if ((c & 0xC0) != 0x80) return;
  }
}

}  // namespace

std::vector<std::string> wrapLines(const std::string& text, float width) {
  std::vector<std::string> lines;
  const ImFont* font = ImGui::GetFont();
  const float size = ImGui::GetFontSize(), scale = size / font->FontSize;
  const char* p = text.c_str();
  const char* end = p + text.size();
  while (p < end) {
    const char* newline = std::find(p, end, '\n');
    const char* wrap = font->CalcWordWrapPositionA(scale, p, newline, std::max(width, size));
    if (wrap == p) {  // a glyph wider than the width: one per line
      ++wrap;
      while (wrap < newline && (static_cast<unsigned char>(*wrap) & 0xC0) == 0x80) ++wrap;
    }
    if (wrap > newline) wrap = newline;
    lines.emplace_back(p, wrap);
    p = wrap;
    while (p < end && *p == ' ') ++p;  // the wrap eats the spaces at the break
    if (p < end && *p == '\n' && p == newline) ++p;
  }
  return lines;
}

bool clippedText(const std::string& text, float width, int maxLines, const ImVec4& colour) {
  std::vector<std::string> lines = wrapLines(text, width);
  const bool cut = int(lines.size()) > maxLines;
  if (cut) {
    lines.resize(std::size_t(std::max(1, maxLines)));
    std::string& last = lines.back();
    while (!last.empty() && ImGui::CalcTextSize((last + kEllipsis).c_str()).x > width) popCodePoint(last);
    last += kEllipsis;
  }
  ImGui::BeginGroup();
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
  ImGui::PopStyleColor();
  ImGui::EndGroup();
  if (cut && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  return cut;
}

}  // namespace hermite::app
