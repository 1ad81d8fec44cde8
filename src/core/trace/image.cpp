#include "core/trace/image.h"

#include <algorithm>
#include <cstdlib>

#include "core/base/errors.h"

namespace hermite {

namespace {

void checkSameSize(std::size_t a, std::size_t b, const char* what) {
  if (a != b) throw InputError(std::string(what) + ": sizes differ (" + std::to_string(a) + " vs " + std::to_string(b) + ")");
}

}  // namespace

void ImageRgba8::fill(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  for (std::size_t p = 0; p + 3 < pixels.size(); p += 4) {
    pixels[p] = r;
    pixels[p + 1] = g;
    pixels[p + 2] = b;
    pixels[p + 3] = a;
  }
}

double maskIoU(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  checkSameSize(a.size(), b.size(), "mask IoU");
  std::size_t both = 0, either = 0;
  for (std::size_t p = 0; p < a.size(); ++p) {
    const bool x = a[p] != 0, y = b[p] != 0;
    both += (x && y);
    either += (x || y);
  }
  return either == 0 ? 1.0 : double(both) / double(either);
}

ImageDiffStats compareImages(const ImageRgba8& a, const ImageRgba8& b, int tolerance) {
  checkSameSize(std::size_t(a.width) * a.height, std::size_t(b.width) * b.height, "image comparison");
  if (a.width != b.width) throw InputError("image comparison: widths differ");
  ImageDiffStats s;
  double sum = 0;
  const std::size_t n = std::size_t(a.width) * a.height;
  for (std::size_t p = 0; p < n; ++p) {
    int worst = 0;
    for (int c = 0; c < 4; ++c) {
      const int d = std::abs(int(a.pixels[4 * p + c]) - int(b.pixels[4 * p + c]));
      worst = std::max(worst, d);
      sum += d;
    }
    s.maxChannelDiff = std::max(s.maxChannelDiff, worst);
    if (worst > tolerance) ++s.pixelsOver;
  }
  s.fractionOver = n ? double(s.pixelsOver) / double(n) : 0.0;
  s.meanAbsDiff = n ? sum / double(4 * n) : 0.0;
  return s;
}

ImageRgba8 diffImage(const ImageRgba8& a, const ImageRgba8& b, int tolerance) {
  checkSameSize(std::size_t(a.width) * a.height, std::size_t(b.width) * b.height, "diff image");
  ImageRgba8 out(a.width, a.height);
  const std::size_t n = std::size_t(a.width) * a.height;
  for (std::size_t p = 0; p < n; ++p) {
    int worst = 0;
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(a.pixels[4 * p + c]) - int(b.pixels[4 * p + c])));
    std::uint8_t* o = out.pixels.data() + 4 * p;
    if (worst > tolerance) {
      o[0] = std::uint8_t(std::min(255, 128 + worst));
      o[1] = o[2] = 0;
    } else {
      const int grey = (int(b.pixels[4 * p]) + b.pixels[4 * p + 1] + b.pixels[4 * p + 2]) / 12 + 160;
      o[0] = o[1] = o[2] = std::uint8_t(grey);
    }
    o[3] = 255;
  }
  return out;
}

}  // namespace hermite
