#pragma once
// The glyph-miss counter: how many glyphs in a frame's draw data were drawn with a font's
// fallback glyph, i.e. text holding a code point the font atlas lacks ("≥" shown as a box).
// Each glyph is one textured quad whose first vertex carries the glyph's atlas corner (U0, V0);
// glyphs are packed apart, so the fallback glyph's corner marks its quads and nothing else.
// With the UI font (ui_font.h) the fallback is U+FFFD, a glyph no message uses on purpose.

struct ImDrawData;

namespace hermite::render {

// Fallback glyphs in `data`, over every font of the current ImGui context's atlas (built).
int countFallbackGlyphs(const ImDrawData& data);

}  // namespace hermite::render
