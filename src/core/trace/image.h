#pragma once
// RGBA8 images (screenshots, reference renders, golden images) and the comparisons image tests use.
// Reading and writing them as PNG is io/png_file.h.

#include <cstdint>
#include <string>
#include <vector>

namespace hermite {

// W × H, 4 bytes per pixel (R, G, B, A), row 0 = top, no padding between rows.
struct ImageRgba8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // W·H·4

  ImageRgba8() = default;
  ImageRgba8(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 4, 0) {}

  std::uint8_t* at(int i, int j) { return pixels.data() + 4 * (std::size_t(j) * width + i); }
  const std::uint8_t* at(int i, int j) const { return pixels.data() + 4 * (std::size_t(j) * width + i); }
  void fill(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255);
  bool operator==(const ImageRgba8&) const = default;
};

// Intersection over union of two W·H masks (non-zero = set); 1 when both are empty.
// InputError when the sizes differ.
double maskIoU(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

struct ImageDiffStats {
  int maxChannelDiff = 0;        // largest |a − b| over all channels and pixels
  std::size_t pixelsOver = 0;    // pixels with some channel differing by more than the tolerance
  double fractionOver = 0;       // pixelsOver / (W·H)
  double meanAbsDiff = 0;        // mean |a − b| over all channels
};
// InputError when the sizes differ.
ImageDiffStats compareImages(const ImageRgba8& a, const ImageRgba8& b, int tolerance);
// A picture of the differences: b dimmed to grey where |a − b| ≤ tolerance, red (brighter =
// larger difference) where some channel differs more.
ImageRgba8 diffImage(const ImageRgba8& a, const ImageRgba8& b, int tolerance);
}  // namespace hermite
