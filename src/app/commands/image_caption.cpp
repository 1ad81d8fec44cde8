#include "app/commands/image_caption.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace hermite::app {

namespace {

// The built-in font's atlas, built once (ImFontAtlas needs no ImGui context).
struct CaptionFont {
  ImFontAtlas atlas;
  ImFont* font = nullptr;
  unsigned char* alpha = nullptr;  // atlas pixels, 1 byte each
  int width = 0, height = 0;
  CaptionFont() {
    font = atlas.AddFontDefault();
    atlas.GetTexDataAsAlpha8(&alpha, &width, &height);
  }
};

const CaptionFont& captionFont() {
  static const CaptionFont font;
  return font;
}

constexpr int kFontPixels = 13;  // ProggyClean's size
constexpr int kPadding = 3;      // above and below each line, at scale 1

// Alpha-blends white glyph coverage `a` (0–255) over pixel p.
void blendWhite(std::uint8_t* p, int a) {
  for (int c = 0; c < 3; ++c) p[c] = std::uint8_t((p[c] * (255 - a) + 255 * a) / 255);
}

// One line of text with its top-left corner at (x0, y0).
void drawLine(ImageRgba8& image, const std::string& text, int x0, int y0, int scale) {
  const CaptionFont& f = captionFont();
  float pen = float(x0);
  for (unsigned char ch : text) {
    const ImFontGlyph* g = f.font->FindGlyph(ImWchar(ch < 128 ? ch : '?'));
    if (!g) continue;
    const int gx0 = int(std::lround(g->U0 * f.width)), gy0 = int(std::lround(g->V0 * f.height));
    const int gw = int(std::lround((g->U1 - g->U0) * f.width)), gh = int(std::lround((g->V1 - g->V0) * f.height));
    for (int j = 0; j < gh * scale; ++j)
      for (int i = 0; i < gw * scale; ++i) {
        const int x = int(pen + g->X0 * scale) + i, y = y0 + int(g->Y0 * scale) + j;
        if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
        const int a = f.alpha[std::size_t(gy0 + j / scale) * std::size_t(f.width) + std::size_t(gx0 + i / scale)];
        if (a > 0) blendWhite(image.at(x, y), a);
      }
    pen += g->AdvanceX * float(scale);
    if (pen >= float(image.width)) break;
  }
}

}  // namespace

int captionLineHeight(int scale) { return (kFontPixels + 2 * kPadding) * std::max(1, scale); }

void burnCaption(ImageRgba8& image, const std::vector<std::string>& lines, int scale) {
  scale = std::max(1, scale);
  const int band = captionLineHeight(scale) * int(lines.size());
  if (lines.empty() || band > image.height) return;
  // A dark band (70 % black over the picture) keeps white text legible on any background.
  for (int y = image.height - band; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(p[c] * 3 / 10);
      p[3] = 255;
    }
  for (std::size_t k = 0; k < lines.size(); ++k)
    drawLine(image, lines[k], 4 * scale,
             image.height - band + int(k) * captionLineHeight(scale) + kPadding * scale, scale);
}

ImageRgba8 shrinkImage(const ImageRgba8& image, int factor) {
  factor = std::max(1, factor);
  if (factor == 1) return image;
  ImageRgba8 out((image.width + factor - 1) / factor, (image.height + factor - 1) / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      int sum[4] = {0, 0, 0, 0}, n = 0;
      for (int j = y * factor; j < std::min(image.height, (y + 1) * factor); ++j)
        for (int i = x * factor; i < std::min(image.width, (x + 1) * factor); ++i, ++n)
          for (int c = 0; c < 4; ++c) sum[c] += image.at(i, j)[c];
      for (int c = 0; c < 4; ++c) out.at(x, y)[c] = std::uint8_t((sum[c] + n / 2) / n);
    }
  return out;
}

ImageRgba8 contactSheet(const std::vector<ImageRgba8>& images, int columns, int gap,
                        const std::array<std::uint8_t, 3>& background) {
  ImageRgba8 sheet(1, 1);
  sheet.fill(background[0], background[1], background[2]);
  if (images.empty()) return sheet;
  columns = std::clamp(columns, 1, int(images.size()));
  const int rows = (int(images.size()) + columns - 1) / columns;
  int tw = 0, th = 0;
  for (const ImageRgba8& im : images) {
    tw = std::max(tw, im.width);
    th = std::max(th, im.height);
  }
  sheet = ImageRgba8(columns * tw + (columns + 1) * gap, rows * th + (rows + 1) * gap);
  sheet.fill(background[0], background[1], background[2]);
  for (std::size_t k = 0; k < images.size(); ++k) {
    const int x0 = gap + int(k % std::size_t(columns)) * (tw + gap), y0 = gap + int(k / std::size_t(columns)) * (th + gap);
    const ImageRgba8& im = images[k];
    for (int y = 0; y < im.height; ++y) std::copy_n(im.at(0, y), 4 * std::size_t(im.width), sheet.at(x0, y0 + y));
  }
  return sheet;
}

}  // namespace hermite::app
