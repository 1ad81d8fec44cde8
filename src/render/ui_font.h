#pragma once
// The UI's typeface: DejaVu Sans (Debian's fonts-dejavu-core), embedded into the binary at build
// time (embed_font.cmake), so `render --ui` draws the same glyphs on every machine. Its glyph
// ranges cover every message the program writes: Latin-1 and Latin Extended-A, Greek, phonetic
// modifiers (ᵀ ᵢ), general punctuation (— … ′), super- and subscripts (⁻ ²), letterlike symbols
// (ℝ), arrows, mathematical operators (≥ ≤ ≠ − ∇), geometric shapes, and U+FFFD: the glyph
// drawn for any code point outside them (glyph_misses.h counts those).
// Needs a current ImGui context; never between NewFrame and Render (the atlas is locked then).

#include <imgui.h>

namespace hermite::render {

// The UI type's pixel height at UI scale 1, and the presenter caption's size relative to it.
inline constexpr float kUiFontPixels = 13.0f;
inline constexpr float kLargeFontFactor = 2.25f;

struct UiFonts {
  ImFont* regular = nullptr;  // the default font: round(kUiFontPixels · scale) px
  ImFont* large = nullptr;    // captions (presenter mode): kLargeFontFactor times that
  float scale = 1.0f;
};

// Replaces the fonts of the current context's atlas with DejaVu Sans rasterised at the scaled
// pixel sizes (crisp type at every scale, not a magnified bitmap) and makes `regular` the
// default. The caller uploads the new atlas (ImGuiRenderer constructor or rebuildFontTexture).
UiFonts loadUiFonts(float scale);

// The zero-terminated code point ranges the atlas holds (pairs of first, last).
const ImWchar* uiGlyphRanges();

}  // namespace hermite::render
