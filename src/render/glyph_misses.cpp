#include "render/glyph_misses.h"

#include <imgui.h>

#include <vector>

namespace hermite::render {

int countFallbackGlyphs(const ImDrawData& data) {
  std::vector<ImVec2> corners;  // (U0, V0) of each font's fallback glyph
  for (const ImFont* font : ImGui::GetIO().Fonts->Fonts)
    if (font->FallbackGlyph) corners.emplace_back(font->FallbackGlyph->U0, font->FallbackGlyph->V0);
  int misses = 0;
  for (int l = 0; l < data.CmdListsCount; ++l)
    for (const ImDrawVert& v : data.CmdLists[l]->VtxBuffer)
      for (const ImVec2& c : corners)
        if (v.uv.x == c.x && v.uv.y == c.y) ++misses;
  return misses;
}

}  // namespace hermite::render
