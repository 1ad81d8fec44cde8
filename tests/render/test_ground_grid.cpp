// The ground grid of the 3D view: on the plane under the lowest sample, perpendicular to up,
// centred under the data, with round spacing.

#include <doctest/doctest.h>

#include <cmath>

#include "render/ground_grid.h"

using namespace hermite;
using namespace hermite::render;

TEST_CASE("ground grid: lines lie on the plane under the lowest sample, across up, with a round spacing") {
  Points<3> P(3, 3);
  P.col(0) = Vec<3>(-1.0, 0.2, 0.5);
  P.col(1) = Vec<3>(2.0, -0.7, 1.0);
  P.col(2) = Vec<3>(0.5, 1.3, -1.5);
  const Box<3> bounds{Vec<3>(-5, -5, -5), Vec<3>(5, 5, 5)};
  const GroundGrid g = groundGrid(P, bounds, Vec<3>(0, 2, 0));  // up need not be unit
  REQUIRE(!g.segments.empty());
  // Extent across y: 3 (x: −1 … 2), 2.5 (z): 1.5 × 3 / 10 = 0.45 → 0.5.
  CHECK(g.spacing == doctest::Approx(0.5).epsilon(1e-12));
  double minX = 1e9, maxX = -1e9;
  for (const auto& [a, b] : g.segments) {
    CHECK(a.y() == doctest::Approx(-0.7).epsilon(1e-12));
    CHECK(b.y() == doctest::Approx(-0.7).epsilon(1e-12));
    minX = std::min({minX, a.x(), b.x()});
    maxX = std::max({maxX, a.x(), b.x()});
  }
  // It reaches past the data on both sides (0.75 × the widest extent from the middle).
  CHECK(minX <= -1.0 - 0.5);
  CHECK(maxX >= 2.0 + 0.5);
  // Lines across x sit on multiples of the spacing.
  for (const auto& [a, b] : g.segments)
    if (std::abs(a.x() - b.x()) < 1e-12) CHECK(std::abs(a.x() / 0.5 - std::round(a.x() / 0.5)) < 1e-9);
}

TEST_CASE("ground grid: without samples it lies under the bounds; a zero up gives none") {
  const Box<3> bounds{Vec<3>(0, 0, -1), Vec<3>(1, 1, 3)};
  const GroundGrid g = groundGrid(Points<3>(3, 0), bounds, Vec<3>(0, 0, 1));
  REQUIRE(!g.segments.empty());
  for (const auto& [a, b] : g.segments) {
    CHECK(a.z() == doctest::Approx(-1.0));
    CHECK(b.z() == doctest::Approx(-1.0));
  }
  CHECK(groundGrid(Points<3>(3, 0), bounds, Vec<3>::Zero()).segments.empty());
  CHECK(groundGrid(Points<3>(3, 0), bounds, Vec<3>(0, NAN, 0)).segments.empty());
}
