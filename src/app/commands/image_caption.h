#pragma once
// Text burnt into a picture on the CPU (sweep's per-image caption and contact sheet): the glyphs
// of Dear ImGui's built-in font (ProggyClean, 13 px, ASCII), read from a font atlas of its own,
// so that no GL or ImGui context is needed and every machine draws the same pixels.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/trace/image.h"

namespace hermite::app {

// Pixel height of one line of caption text at `scale` (1: 13 px glyphs plus padding).
int captionLineHeight(int scale);

// Draws `lines` (ASCII; other bytes draw as '?') in white on a dark band across the bottom of
// `image`, each glyph magnified by `scale` (≥ 1, nearest neighbour); text past the right edge is
// cut. The band is as tall as the lines; an image shorter than that is left unchanged.
void burnCaption(ImageRgba8& image, const std::vector<std::string>& lines, int scale = 1);

// `image` reduced by an integer `factor` (≥ 1): each output pixel the mean of a factor × factor
// block (edge blocks of the partial size), so thin curves fade rather than vanish.
ImageRgba8 shrinkImage(const ImageRgba8& image, int factor);

// `images` (each with its caption already burnt in) tiled row by row, `columns` per row (≥ 1),
// every tile the size of the largest, separated and framed by `gap` pixels of `background`
// (RGB). An empty list gives a 1 × 1 image of the background.
ImageRgba8 contactSheet(const std::vector<ImageRgba8>& images, int columns, int gap = 8,
                        const std::array<std::uint8_t, 3>& background = {255, 255, 255});

}  // namespace hermite::app
