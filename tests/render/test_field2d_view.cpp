#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/rbf/hrbf.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/presets.h"
#include "core/trace/color_map.h"
#include "core/trace/field2d_reference.h"
#include "render/field2d_view.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

bool isZeroColor(const ImageRgba8& image, int i, int j) {
  const std::uint8_t* p = image.at(i, j);
  return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

// Largest Chebyshev distance (pixels) from a zero-colour pixel of `a` to the nearest one of `b`;
// 1000 when `b` has none near (searched up to 3 px).
int zeroCurveDistance(const ImageRgba8& a, const ImageRgba8& b) {
  int worst = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) {
      if (!isZeroColor(a, i, j)) continue;
      int best = 1000;
      for (int r = 0; r <= 3 && best == 1000; ++r)
        for (int dj = -r; dj <= r; ++dj)
          for (int di = -r; di <= r; ++di) {
            const int x = i + di, y = j + dj;
            if (x >= 0 && y >= 0 && x < b.width && y < b.height && isZeroColor(b, x, y)) best = std::min(best, r);
          }
      worst = std::max(worst, best);
    }
  return worst;
}

int countZero(const ImageRgba8& a) {
  int n = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) n += isZeroColor(a, i, j) ? 1 : 0;
  return n;
}

// Pixels whose channels differ from the reference by more than `tolerance`.
int pixelsOver(const ImageRgba8& a, const ImageRgba8& b, int tolerance) {
  return int(compareImages(a, b, tolerance).pixelsOver);
}

}  // namespace

TEST_CASE("2D field view of a circle matches the CPU reference") {
  auto context = testing::makeTestContext();
  const Vec<2> c(0.1, -0.2);
  const CircleField circle(c, 0.9);
  const View2d view(Vec<2>(0, 0), 1.5, 160, 120);
  Field2dViewOptions options;
  options.arrowHeadPx = 0;  // the reference draws plain normals
  const ImageRgba8 gpu = renderField2d(circle, view, options);
  const Field2dImage ref = renderField2dReference(circle, view, options.style);

  const int zeros = countZero(gpu);
  CHECK(zeros > 100);
  CHECK(std::abs(zeros - countZero(ref.image)) <= zeros / 20);
  CHECK(zeroCurveDistance(gpu, ref.image) <= 1);
  CHECK(zeroCurveDistance(ref.image, gpu) <= 1);
  // Same colours up to float-vs-double rounding.
  CHECK(pixelsOver(gpu, ref.image, 2) <= gpu.width * gpu.height / 1000);

  // Heat map sign: blue (f < 0) at the centre, red (f > 0) in the corners.
  const Vec<2> centre = view.worldToPixel(c);
  const std::uint8_t* in = gpu.at(int(centre.x()), int(centre.y()));
  CHECK(in[2] > in[0] + 60);
  const std::uint8_t* out = gpu.at(2, 2);
  CHECK(out[0] > out[2] + 60);
}

TEST_CASE("2D field view of a fitted curve2d HRBF with samples matches the reference, deterministically") {
  auto context = testing::makeTestContext();
  const HermiteSamples<2> samples = makePreset2d("curve2d", 40);
  HrbfOptions ho;
  ho.kernel = Kernel{KernelType::Gaussian, 0.4};
  const HrbfModel<2> model = fitHrbf(samples, ho);
  const View2d view(Vec<2>(0.05, 0), 1.25, 200, 150);
  Field2dViewOptions options;
  options.arrowHeadPx = 0;
  const ImageRgba8 gpu = renderField2d(model, view, options, samples.points, samples.normals);
  const Field2dImage ref = renderField2dReference(model, view, options.style, samples.points, samples.normals);

  CHECK(countZero(gpu) > 200);
  CHECK(zeroCurveDistance(gpu, ref.image) <= 1);
  CHECK(zeroCurveDistance(ref.image, gpu) <= 1);
  CHECK(pixelsOver(gpu, ref.image, 3) <= gpu.width * gpu.height / 200);

  // Inside / outside by the sign of f at the pixel centres, judged by the heat map's hue where
  // no line or mark is near (|f| well above the line's reach).
  int checked = 0;
  for (int j = 0; j < view.height(); j += 7)
    for (int i = 0; i < view.width(); i += 7) {
      const double f = ref.value[std::size_t(j) * view.width() + i];
      if (std::abs(f) < 0.25 * ref.range) continue;
      const std::uint8_t* p = gpu.at(i, j);
      if (f < 0) CHECK(int(p[2]) > int(p[0]));
      else CHECK(int(p[0]) > int(p[2]));
      ++checked;
    }
  CHECK(checked > 50);

  const ImageRgba8 again = renderField2d(model, view, options, samples.points, samples.normals);
  CHECK(again == gpu);
}

TEST_CASE("2D field view: coarser evaluation grids keep the zero curve within a pixel") {
  auto context = testing::makeTestContext();
  const CircleField circle(Vec<2>(0, 0), 0.8);
  const HermiteSamples<2> samples = makePreset2d("curve2d", 200);
  HrbfOptions ho;
  ho.kernel = Kernel{KernelType::Cubic, 1.0};
  const HrbfModel<2> model = fitHrbf(samples, ho);
  const View2d view(Vec<2>(0, 0), 1.25, 256, 256);
  for (double scale : {0.5, 0.25, 1.0 / 6, 0.125}) {
    CAPTURE(scale);
    Field2dViewOptions options;
    options.gridScale = scale;
    options.style.range = 1.0;  // the coarse grid misses the exact max |f|: fix the range
    for (const ImplicitField<2>* field : {static_cast<const ImplicitField<2>*>(&circle),
                                          static_cast<const ImplicitField<2>*>(&model)}) {
      const ImageRgba8 gpu = renderField2d(*field, view, options);
      const Field2dImage ref = renderField2dReference(*field, view, options.style);
      CHECK(countZero(gpu) > 100);
      CHECK(zeroCurveDistance(gpu, ref.image) <= 1);
      CHECK(zeroCurveDistance(ref.image, gpu) <= 1);
    }
  }
}

TEST_CASE("2D field view: outside view.bounds the zero curve is not drawn and the map fades") {
  auto context = testing::makeTestContext();
  const CircleField circle(Vec<2>(0, 0), 0.8);
  const View2d view(Vec<2>(0, 0), 1.2, 128, 128);
  Field2dViewOptions options;
  options.bounds = Box<2>{Vec<2>(0, -2), Vec<2>(2, 2)};  // the right half only
  const ImageRgba8 gpu = renderField2d(circle, view, options);
  const Vec<2> left = view.worldToPixel(Vec<2>(-0.8, 0));
  const Vec<2> right = view.worldToPixel(Vec<2>(0.8, 0));
  CHECK_FALSE(isZeroColor(gpu, int(left.x()), int(left.y())));
  CHECK(isZeroColor(gpu, int(right.x()), int(right.y())));
  // Faded: brighter than the same |f| inside.
  const std::uint8_t* a = gpu.at(int(view.worldToPixel(Vec<2>(-0.3, 0.1)).x()), int(view.worldToPixel(Vec<2>(-0.3, 0.1)).y()));
  const std::uint8_t* b = gpu.at(int(view.worldToPixel(Vec<2>(0.3, 0.1)).x()), int(view.worldToPixel(Vec<2>(0.3, 0.1)).y()));
  CHECK(int(a[0]) > int(b[0]));
}
