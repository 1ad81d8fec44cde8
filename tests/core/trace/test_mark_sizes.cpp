// Sample marks of the 2D view scaled to the mean sample spacing: sparse clouds keep the style's
// sizes, dense ones get normals of at most two spacings and dots of at most half a spacing, and
// samples less than 2 px apart no dots.

#include <doctest/doctest.h>

#include "core/trace/mark_sizes.h"

using namespace hermite;

namespace {

// n samples on a row, `step` world units apart.
Points<2> row(int n, double step) {
  Points<2> p(2, n);
  for (int i = 0; i < n; ++i) p.col(i) = Vec<2>(i * step, 0.0);
  return p;
}

}  // namespace

TEST_CASE("mark sizes: sparse samples keep the style's sizes, dense ones shrink with the spacing") {
  const View2d view(Vec<2>(0, 0), 1.0, 200, 200);  // 100 px per world unit
  const Field2dStyle style;                       // normals 18 px, dots of radius 3 px
  const MarkSizes sparse = markSizes2d(style, view, row(5, 0.3));  // 30 px apart
  CHECK(sparse.normalLengthPx == style.normalLengthPx);
  CHECK(sparse.pointRadiusPx == style.pointRadiusPx);
  const MarkSizes dense = markSizes2d(style, view, row(50, 0.04));  // 4 px apart
  CHECK(dense.normalLengthPx == doctest::Approx(8.0).epsilon(1e-9));  // 2 spacings
  CHECK(dense.pointRadiusPx == doctest::Approx(1.5).epsilon(1e-12));  // the floor
  const MarkSizes carpet = markSizes2d(style, view, row(200, 0.015));  // 1.5 px apart: no dots
  CHECK(carpet.pointRadiusPx == 0);
  CHECK(carpet.normalLengthPx == doctest::Approx(3.0).epsilon(1e-9));
  const MarkSizes one = markSizes2d(style, view, row(1, 0.0));
  CHECK(one.normalLengthPx == style.normalLengthPx);
}
