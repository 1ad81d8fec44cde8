// The r explorer's plot mapping: log r ↔ pixel, and ticks a student can read.

#include <doctest/doctest.h>

#include <cmath>

#include "app/gui/log_axis.h"

using namespace hermite::app;

TEST_CASE("log axis: r maps linearly in log10 to pixels and back; bounds and clicks clamp") {
  const LogAxis x(0.01, 10, 100, 400);  // three decades over 300 px
  CHECK(x.toPixel(0.01) == doctest::Approx(100));
  CHECK(x.toPixel(0.1) == doctest::Approx(200));
  CHECK(x.toPixel(1) == doctest::Approx(300));
  CHECK(x.toPixel(10) == doctest::Approx(400));
  CHECK(x.toPixel(0) == 100);  // not a radius: the left edge
  for (double r : {0.0123, 0.5, 7.7}) CHECK(x.fromPixel(x.toPixel(r)) == doctest::Approx(r).epsilon(1e-12));
  CHECK(x.fromPixel(50) == doctest::Approx(0.01));  // a click left of the plot clamps
  CHECK(x.fromPixel(999) == doctest::Approx(10));
  // One radius: the range is widened a half decade either side, so the point sits in the middle.
  const LogAxis one(0.2, 0.2, 0, 100);
  CHECK(one.toPixel(0.2) == doctest::Approx(50));
}

TEST_CASE("log axis: one labelled tick per decade, or 1-2-5 ticks inside a short range") {
  const LogAxis wide(0.01, 10, 0, 300);
  const std::vector<AxisTick> t = wide.ticks();
  REQUIRE(t.size() == 4);
  CHECK(t[0].label == "0.01");
  CHECK(t[1].label == "0.1");
  CHECK(t[2].label == "1");
  CHECK(t[3].label == "10");
  CHECK(t[2].pixel == doctest::Approx(200));
  // The explorer's default, 0.03 … 0.9: one decade (0.1) inside, so 1-2-5 multiples instead.
  const std::vector<AxisTick> s = LogAxis(0.03, 0.9, 0, 300).ticks();
  REQUIRE(s.size() >= 2);
  CHECK(s.front().label == "0.05");
  CHECK(s.back().label == "0.5");
  for (const AxisTick& k : s) {
    CHECK(k.value >= 0.03);
    CHECK(k.value <= 0.9);
    CHECK(k.pixel >= 0);
    CHECK(k.pixel <= 300);
  }
}
