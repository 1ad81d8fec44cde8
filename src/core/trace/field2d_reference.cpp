#include "core/trace/field2d_reference.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/trace/color_map.h"
#include "core/trace/mark_sizes.h"
#include "core/trace/shading.h"

namespace hermite {

namespace {

// Anti-aliased coverage of a line of full width w at distance d pixels from its centre line:
// a 1-pixel linear ramp centred on the edge.
double coverage(double d, double w) { return std::clamp(0.5 * w + 0.5 - d, 0.0, 1.0); }

Vec<3> toVec(const std::array<double, 3>& a) { return Vec<3>(a[0], a[1], a[2]); }

// Blends `color` into the linear-colour buffer over the pixels within `reach` of the segment a–b
// (pixel coordinates), with coverage(distance, width).
void drawSegment(std::vector<Vec<3>>& buffer, int W, int H, const Vec<2>& a, const Vec<2>& b, double width,
                 const Vec<3>& color) {
  const double reach = 0.5 * width + 1.0;
  const int i0 = std::max(0, int(std::floor(std::min(a.x(), b.x()) - reach)));
  const int i1 = std::min(W - 1, int(std::ceil(std::max(a.x(), b.x()) + reach)));
  const int j0 = std::max(0, int(std::floor(std::min(a.y(), b.y()) - reach)));
  const int j1 = std::min(H - 1, int(std::ceil(std::max(a.y(), b.y()) + reach)));
  const Vec<2> ab = b - a;
  const double len2 = ab.squaredNorm();
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Vec<2> p(i + 0.5, j + 0.5);
      const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const double c = coverage((p - (a + s * ab)).norm(), width);
      if (c > 0) buffer[std::size_t(j) * W + i] = (1 - c) * buffer[std::size_t(j) * W + i] + c * color;
    }
}

// The linear colour of a pixel with data: the diverging map of f, iso-lines darkened over it
// and the zero curve on top, each with its anti-aliased coverage (`zeroCoverage` the last).
Vec<3> pixelColor(double v, double gradPx, const Field2dStyle& style, double range, double isoSpacing,
                  float& zeroCoverage) {
  Vec<3> c = divergingColor(v, range);
  if (isoSpacing > 0) {
    const double k = std::round(v / isoSpacing);
    if (k != 0) {
      const double d = gradPx > 0 ? std::abs(v - k * isoSpacing) / gradPx : std::numeric_limits<double>::infinity();
      const double cov = coverage(d, style.isoWidthPx);
      c = (1 - cov) * c + cov * (kIsoLineDarken * c);
    }
  }
  const double d0 = v == 0 ? 0.0 : gradPx > 0 ? std::abs(v) / gradPx : std::numeric_limits<double>::infinity();
  const double cov0 = coverage(d0, style.zeroWidthPx);
  zeroCoverage = float(cov0);
  return (1 - cov0) * c + cov0 * toVec(kZeroCurveColor);
}

// Normals, then sample dots over them, scaled to the sample spacing (mark_sizes.h).
void drawSampleMarks(std::vector<Vec<3>>& color, const View2d& view, const Field2dStyle& style,
                     const Points<2>& points, const Points<2>& normals) {
  const int W = view.width(), H = view.height();
  const MarkSizes marks = markSizes2d(style, view, points);
  if (normals.cols() == points.cols() && marks.normalLengthPx > 0)
    for (Eigen::Index s = 0; s < points.cols(); ++s) {
      const Vec<2> a = view.worldToPixel(points.col(s));
      const Vec<2> nrm = normals.col(s).normalized();
      const Vec<2> b = a + marks.normalLengthPx * Vec<2>(nrm.x(), -nrm.y());  // rows grow downwards
      drawSegment(color, W, H, a, b, 1.5, toVec(style.normalColor));
    }
  if (marks.pointRadiusPx > 0)
    for (Eigen::Index s = 0; s < points.cols(); ++s) {
      const Vec<2> a = view.worldToPixel(points.col(s));
      drawSegment(color, W, H, a, a, 2.0 * marks.pointRadiusPx, toVec(style.pointColor));
    }
}

}  // namespace

Field2dImage renderField2dReference(const ImplicitField<2>& field, const View2d& view, const Field2dStyle& style,
                                    const Points<2>& points, const Points<2>& normals) {
  const auto t0 = std::chrono::steady_clock::now();
  const int W = view.width(), H = view.height();
  const std::size_t n = std::size_t(W) * H;
  Points<2> X(2, Eigen::Index(n));
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) X.col(Eigen::Index(j) * W + i) = view.pixelCenter(i, j);
  Eigen::VectorXd f;
  Points<2> G;
  field.evaluateBatch(X, f, &G);
  std::vector<char> valid;
  field.validBatch(X, valid);

  Field2dImage out;
  out.range = style.range;
  if (!(out.range > 0)) {
    double m = 0;
    for (Eigen::Index p = 0; p < f.size(); ++p)
      if (valid[std::size_t(p)] && std::isfinite(f(p))) m = std::max(m, std::abs(f(p)));
    out.range = m > 0 ? m : 1.0;
  }
  out.isoSpacing = style.isoSpacing == 0 ? niceIsoSpacing(out.range) : style.isoSpacing;
  out.value.resize(n);
  out.zeroCoverage.resize(n);

  const double px = view.pixelSize();
  std::vector<Vec<3>> color(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < std::ptrdiff_t(n); ++p) {
    out.value[p] = float(f(p));
    if (valid[std::size_t(p)]) {
      color[p] = pixelColor(f(p), G.col(p).norm() * px, style, out.range, out.isoSpacing, out.zeroCoverage[p]);
    } else {
      const int i = int(p % W), row = H - 1 - int(p / W);  // GL row: 0 at the bottom
      const bool hatch = (i + row) % kNoDataHatchPeriod < kNoDataHatchWidth;
      color[p] = toVec(hatch ? kNoDataHatchColor : kNoDataColor);
      out.zeroCoverage[p] = 0.0f;
    }
  }
  drawSampleMarks(color, view, style, points, normals);

  out.image = ImageRgba8(W, H);
  for (std::size_t p = 0; p < n; ++p) {
    std::uint8_t* o = out.image.pixels.data() + 4 * p;
    for (int k = 0; k < 3; ++k) o[k] = shading::toByte(color[p](k));
    o[3] = 255;
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace hermite
