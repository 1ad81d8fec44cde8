#include "render/field2d_view.h"
#include "core/base/ms_since.h"
#include "render/gl/glm_convert.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/base/errors.h"
#include "core/trace/mark_sizes.h"
#include "core/trace/color_map.h"
#include "render/gl/offscreen.h"
#include "render/gl/shader_library.h"

namespace hermite::render {

namespace {

using Clock = std::chrono::steady_clock;

// One instance of marks2d.vert: segment in GL pixel coordinates, colour and full width.
struct Mark {
  float ax, ay, bx, by;
  float r, g, b, width;
};

// Grid point (a, b), b = 0 at the bottom (GL row order), sits at GL pixel coordinates
// ((a + ½)·W/gw, (b + ½)·H/gh); with gw = W, gh = H these are the pixel centres. World
// coordinates, column b·gw + a.
Points<2> gridPoints(const View2d& view, int gw, int gh) {
  const int W = view.width(), H = view.height();
  Points<2> X(2, Eigen::Index(gw) * gh);
  const double sx = double(W) / gw, sy = double(H) / gh;
#pragma omp parallel for schedule(static)
  for (int b = 0; b < gh; ++b)
    for (int a = 0; a < gw; ++a)
      X.col(Eigen::Index(b) * gw + a) = view.pixelToWorld((a + 0.5) * sx, H - (b + 0.5) * sy);
  return X;
}

// RGBA32F texels (f, ∂f/∂x, ∂f/∂y, 1 where there is no data), not RGB32F: llvmpipe fetches
// 3-channel float textures through a slow generic path.
std::vector<float> fieldTexels(const Eigen::VectorXd& f, const Points<2>& G, const std::vector<char>& valid) {
  const std::ptrdiff_t n = f.size();
  std::vector<float> texels(4 * std::size_t(n));
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < n; ++p) {
    texels[4 * p] = float(f(p));
    texels[4 * p + 1] = float(G(0, p));
    texels[4 * p + 2] = float(G(1, p));
    texels[4 * p + 3] = valid[std::size_t(p)] ? 0.0f : 1.0f;
  }
  return texels;
}

// The colour range when none is given: the largest finite |f| with data (inside `bounds` when
// set), 1 if that is 0.
double automaticRange(const Eigen::VectorXd& f, const std::vector<char>& valid, const Points<2>& X,
                      const std::optional<Box<2>>& bounds) {
  double m = 0;
  for (Eigen::Index p = 0; p < f.size(); ++p) {
    if (!valid[std::size_t(p)] || !std::isfinite(f(p))) continue;
    if (bounds && !bounds->contains(X.col(p))) continue;
    m = std::max(m, std::abs(f(p)));
  }
  return m > 0 ? m : 1.0;
}

// Marks in GL pixels: normals (with arrow heads) first, then the dots on top, as the reference
// draws them, scaled to the mean sample spacing (mark_sizes.h).
std::vector<Mark> sampleMarks(const View2d& view, const Field2dViewOptions& options, const Points<2>& points,
                              const Points<2>& normals) {
  std::vector<Mark> marks;
  const int H = view.height();
  const auto toGl = [&](const Vec<2>& world) {
    const Vec<2> p = view.worldToPixel(world);
    return Vec<2>(p.x(), H - p.y());
  };
  const auto add = [&](const Vec<2>& a, const Vec<2>& b, double width, const std::array<double, 3>& c) {
    marks.push_back({float(a.x()), float(a.y()), float(b.x()), float(b.y()), float(c[0]), float(c[1]), float(c[2]),
                     float(width)});
  };
  const Field2dStyle& st = options.style;
  const MarkSizes marksPx = markSizes2d(st, view, points);
  const double normalPx = marksPx.normalLengthPx, dotRadiusPx = marksPx.pointRadiusPx;
  if (options.showNormals && normals.cols() == points.cols() && normalPx > 0)
    for (Eigen::Index s = 0; s < points.cols(); ++s) {
      const double len = normals.col(s).norm();
      if (!(len > 0) || !points.col(s).allFinite()) continue;
      const Vec<2> a = toGl(points.col(s));
      const Vec<2> dir = normals.col(s) / len;  // GL pixels have +y up like the world
      const Vec<2> b = a + normalPx * dir;
      add(a, b, 1.5, st.normalColor);
      if (options.arrowHeadPx > 0) {
        const Vec<2> side(-dir.y(), dir.x());
        const double h = std::min(options.arrowHeadPx, 0.4 * normalPx);  // 18 px normals keep 5 px barbs
        add(b, b - h * (0.87 * dir + 0.5 * side), 1.5, st.normalColor);  // barbs at ±30°
        add(b, b - h * (0.87 * dir - 0.5 * side), 1.5, st.normalColor);
      }
    }
  if (options.showPoints && dotRadiusPx > 0)
    for (Eigen::Index s = 0; s < points.cols(); ++s) {
      if (!points.col(s).allFinite()) continue;
      const Vec<2> a = toGl(points.col(s));
      add(a, a, 2.0 * dotRadiusPx, st.pointColor);
    }
  return marks;
}

}  // namespace

Field2dView::Field2dView()
    : heat_(buildProgram({"fullscreen.vert", "field2d.frag"})), marks_(buildProgram({"marks2d.vert", "marks2d.frag"})) {
  marksVao_.setVertexBuffer(0, marksBuffer_, 0, sizeof(Mark));
  marksVao_.setAttribute(0, 0, 4, GL_FLOAT, false, 0);
  marksVao_.setAttribute(1, 0, 4, GL_FLOAT, false, 4 * sizeof(float));
  glVertexArrayBindingDivisor(marksVao_.id(), 0, 1);  // one segment per instance
  checkGl("Field2dView vertex arrays");
}

void Field2dView::setField(const ImplicitField<2>& field, const View2d& view, const Field2dViewOptions& options,
                           const Points<2>& points, const Points<2>& normals) {
  const auto t0 = Clock::now();
  const double scale = std::clamp(options.gridScale, 0.05, 1.0);
  const int gw = std::max(1, int(std::lround(view.width() * scale)));
  const int gh = std::max(1, int(std::lround(view.height() * scale)));
  const Points<2> X = gridPoints(view, gw, gh);
  Eigen::VectorXd f;
  Points<2> G;
  field.evaluateBatch(X, f, &G);
  std::vector<char> valid;
  field.validBatch(X, valid);
  const std::vector<float> texels = fieldTexels(f, G, valid);
  range_ = options.style.range > 0 ? options.style.range : automaticRange(f, valid, X, options.bounds);
  isoSpacing_ = options.style.isoSpacing == 0 ? niceIsoSpacing(range_) : options.style.isoSpacing;
  evaluateMs_ = msSince(t0);

  const auto t1 = Clock::now();
  if (!field_.valid() || gw != gridW_ || gh != gridH_) {
    field_ = Texture::create2D(GL_RGBA32F, gw, gh);
    field_.setWrap(GL_CLAMP_TO_EDGE);
  }
  field_.upload2D(GL_RGBA, GL_FLOAT, texels.data());
  gridW_ = gw;
  gridH_ = gh;
  view_ = view;
  options_ = options;
  const std::vector<Mark> marks = sampleMarks(view, options, points, normals);
  markCount_ = int(marks.size());
  if (!marks.empty()) {
    marksBuffer_.setData(marks.data(), marks.size() * sizeof(Mark));
    marksVao_.setVertexBuffer(0, marksBuffer_, 0, sizeof(Mark));
  }
  checkGl("Field2dView::setField");
  uploadMs_ = msSince(t1);
}

void Field2dView::draw() {
  if (!view_ || !field_.valid()) throw EnvironmentError("Field2dView::draw before setField");
  const View2d& view = *view_;
  const int W = view.width(), H = view.height();
  const Field2dStyle& st = options_.style;

  const GLboolean blend = glIsEnabled(GL_BLEND);
  const GLboolean depth = glIsEnabled(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);

  heat_.use();
  field_.bind(0);
  const bool pixelGrid = gridW_ == W && gridH_ == H;
  field_.setFilter(pixelGrid ? GL_NEAREST : GL_LINEAR, pixelGrid ? GL_NEAREST : GL_LINEAR);
  heat_.setUniform("u_field", 0);
  heat_.setUniform("u_viewport", glm::vec2(float(W), float(H)));
  heat_.setUniform("u_pixel_size", float(view.pixelSize()));
  heat_.setUniform("u_range", float(range_));
  heat_.setUniform("u_iso_spacing", float(isoSpacing_));
  heat_.setUniform("u_zero_width", float(st.zeroWidthPx));
  heat_.setUniform("u_iso_width", float(st.isoWidthPx));
  heat_.setUniform("u_iso_darken", float(kIsoLineDarken));
  heat_.setUniform("u_zero_color", toGlm(kZeroCurveColor));
  heat_.setUniform("u_no_data_color", toGlm(kNoDataColor));
  heat_.setUniform("u_no_data_hatch_color", toGlm(kNoDataHatchColor));
  heat_.setUniform("u_no_data_hatch", glm::ivec2(kNoDataHatchPeriod, kNoDataHatchWidth));
  if (options_.bounds) {
    const Vec<2> lo = view.worldToPixel(options_.bounds->lo);  // image rows grow downwards
    const Vec<2> hi = view.worldToPixel(options_.bounds->hi);
    heat_.setUniform("u_bounds_px", glm::vec4(float(lo.x()), float(H - lo.y()), float(hi.x()), float(H - hi.y())));
  }
  heat_.setUniform("u_use_bounds", options_.bounds ? 1 : 0);
  heat_.setUniform("u_outside_color", toGlm(options_.outsideColor));
  heat_.setUniform("u_outside_mix", float(options_.outsideMix));
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  checkGl("Field2dView heat map");

  if (markCount_ > 0) {
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    // Alpha stays 1: the framebuffer is an opaque screenshot.
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    marks_.use();
    marks_.setUniform("u_viewport", glm::vec2(float(W), float(H)));
    marksVao_.bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, markCount_);
    checkGl("Field2dView marks");
  }
  glBindVertexArray(0);
  if (blend) glEnable(GL_BLEND); else glDisable(GL_BLEND);
  if (depth) glEnable(GL_DEPTH_TEST);
}

ImageRgba8 renderField2d(const ImplicitField<2>& field, const View2d& view, const Field2dViewOptions& options,
                         const Points<2>& points, const Points<2>& normals) {
  Field2dView v;
  v.setField(field, view, options, points, normals);
  OffscreenTarget target(view.width(), view.height(), false);
  target.bind();
  v.draw();
  return target.read();
}

}  // namespace hermite::render
