#include <doctest/doctest.h>

#include "core/shapes/analytic_shapes.h"
#include "core/trace/color_map.h"
#include "core/trace/field2d_reference.h"

using namespace hermite;

TEST_CASE("field2d reference: the zero curve of a circle lies within 1 px of the analytic circle") {
  const Vec<2> c(0.1, -0.2);
  const double R = 0.9;
  const CircleField circle(c, R);
  const View2d view(Vec<2>(0, 0), 1.5, 120, 96);
  const Field2dImage out = renderField2dReference(circle, view);
  CHECK(out.range > 0);
  CHECK(out.isoSpacing > 0);
  int black = 0;
  for (int j = 0; j < view.height(); ++j)
    for (int i = 0; i < view.width(); ++i) {
      const std::size_t p = std::size_t(j) * view.width() + i;
      const double dPx = std::abs((view.pixelCenter(i, j) - c).norm() - R) / view.pixelSize();
      const std::uint8_t* px = out.image.at(i, j);
      const bool isZeroColor = px[0] == 0 && px[1] == 0 && px[2] == 0;
      if (isZeroColor) {
        ++black;
        CHECK(dPx <= 1.0);
      }
      if (dPx <= 0.5) CHECK(isZeroColor);
      if (dPx >= 2.0) CHECK(out.zeroCoverage[p] == 0.0f);
      // Row 0 is the top: f at the pixel centre matches the field there.
      CHECK(out.value[p] == doctest::Approx(circle.value(view.pixelCenter(i, j))).epsilon(1e-6));
    }
  CHECK(black > 2 * M_PI * R / view.pixelSize());  // a closed curve, ≥ one pixel per pixel of arc
  // Far from the curve the pixel is exactly the map colour (inside: bluish).
  const Vec<2> inside = view.worldToPixel(c);
  const std::uint8_t* px = out.image.at(int(inside.x()), int(inside.y()));
  CHECK(px[2] > px[0]);
}

TEST_CASE("field2d reference: samples drawn as dots") {
  const CircleField circle;
  const View2d view(Vec<2>(0, 0), 1.5, 64, 64);
  Points<2> pts(2, 1), nrm(2, 1);
  pts.col(0) = Vec<2>(1, 0);
  nrm.col(0) = Vec<2>(1, 0);
  Field2dStyle style;
  style.pointColor = {1, 0, 1};
  const Field2dImage out = renderField2dReference(circle, view, style, pts, nrm);
  const Vec<2> p = view.worldToPixel(Vec<2>(1, 0));
  const std::uint8_t* px = out.image.at(int(p.x()), int(p.y()));
  CHECK(int(px[0]) == 255);
  CHECK(int(px[1]) == 0);
}
