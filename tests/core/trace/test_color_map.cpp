#include <doctest/doctest.h>

#include "core/trace/color_map.h"

using namespace hermite;

TEST_CASE("color map: symmetric about 0, white-ish at 0, zero-curve colour not in the map") {
  double minDistance = 1e9;
  for (int k = 0; k <= 2000; ++k) {
    const double t = -1.0 + k / 1000.0;
    const Vec<3> c = divergingColorAt(t), m = divergingColorAt(-t);
    // Mirror: the colour at −t is the colour at t with red and blue swapped.
    CHECK(std::abs(c.x() - m.z()) < 1e-12);
    CHECK(std::abs(c.y() - m.y()) < 1e-12);
    CHECK(std::abs(c.z() - m.x()) < 1e-12);
    minDistance = std::min(minDistance, (c - Vec<3>(kZeroCurveColor[0], kZeroCurveColor[1], kZeroCurveColor[2])).norm());
    // Iso-line colours are darkened map colours, also distinct from the zero curve.
    minDistance = std::min(minDistance, (kIsoLineDarken * c).norm());
  }
  CHECK(minDistance > 0.4);
  CHECK(divergingColorAt(0.0).minCoeff() > 0.9);
  CHECK(divergingColorAt(-1.0).z() > divergingColorAt(-1.0).x());  // inside blue
  CHECK(divergingColorAt(1.0).x() > divergingColorAt(1.0).z());    // outside red
  CHECK((divergingColor(5.0, 2.0) - divergingColorAt(1.0)).norm() == 0.0);  // clamped
  CHECK(niceIsoSpacing(1.0) == doctest::Approx(0.2));
  CHECK(niceIsoSpacing(0.37) == doctest::Approx(0.05));
  CHECK(niceIsoSpacing(30.0) == doctest::Approx(5.0));
}
