// The "far from the samples" test of the stray-pocket review (occupied_cells.h): within one cell
// of a sample is near, beyond 2√3 cells far, on grids far finer than a bit per cell could hold;
// the samples within a radius are the brute-force search's.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/mesh/occupied_cells.h"

using namespace hermite;

TEST_CASE("occupied cells: near within a cell of a sample, far beyond 2√3 cells") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  Points<3> samples(3, 300);
  for (Eigen::Index i = 0; i < samples.cols(); ++i) samples.col(i) = Vec<3>(u(rng), u(rng), u(rng));
  const double cell = 0.02;
  const OccupiedCells occupied(samples, Vec<3>::Zero(), cell);
  int near = 0, far = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec<3> x(u(rng), u(rng), u(rng));
    const double d = (samples.colwise() - x).colwise().norm().minCoeff();
    if (d < cell) {
      CHECK_FALSE(occupied.farFromSamples(x));
      ++near;
    }
    if (d > 2 * std::sqrt(3.0) * cell) {
      CHECK(occupied.farFromSamples(x));
      ++far;
    }
  }
  CHECK(near > 10);  // both sides were tried
  CHECK(far > 1000);
}

TEST_CASE("occupied cells: cells far finer than the extent, and points beyond the keys' range") {
  Points<3> samples(3, 3);
  samples.col(0) = Vec<3>(0, 0, 0);
  samples.col(1) = Vec<3>(1000, -1000, 1000);
  samples.col(2) = Vec<3>(1e12, 0, 0);  // beyond 2²⁰ cells: shares the outermost cells
  const OccupiedCells occupied(samples, Vec<3>::Zero(), 1e-3);  // 10⁶ cells per unit
  CHECK_FALSE(occupied.farFromSamples(Vec<3>(0.0005, 0.0005, 0)));
  CHECK(occupied.farFromSamples(Vec<3>(0.01, 0, 0)));
  CHECK_FALSE(occupied.farFromSamples(Vec<3>(1000.001, -1000, 1000)));
  CHECK(occupied.farFromSamples(Vec<3>(500, 0, 0)));
  CHECK_FALSE(occupied.farFromSamples(Vec<3>(2e12, 0, 0)));  // clamped: a false near, never a false far
}

TEST_CASE("occupied cells: the samples within a radius are exactly those a brute-force search finds") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  Points<3> samples(3, 2000);
  for (Eigen::Index i = 0; i < samples.cols(); ++i) samples.col(i) = Vec<3>(u(rng), u(rng), u(rng));
  const OccupiedCells occupied(samples, Vec<3>::Constant(-0.5), 0.03);
  std::vector<int> within;
  for (int k = 0; k < 500; ++k) {
    const Vec<3> x(u(rng), u(rng), u(rng));
    const double r = 0.01 + 0.07 * u(rng);  // up to about 2.7 cells
    std::vector<int> expected;
    for (Eigen::Index i = 0; i < samples.cols(); ++i)
      if ((samples.col(i) - x).norm() <= r) expected.push_back(static_cast<int>(i));
    occupied.samplesWithin(x, r, within);
    std::sort(within.begin(), within.end());
    REQUIRE(within == expected);
    occupied.samplesWithin(x, r, within, 1);  // at most one, and one whenever there is any
    REQUIRE(within.size() == std::min<std::size_t>(1, expected.size()));
    if (!within.empty()) CHECK((samples.col(within[0]) - x).norm() <= r);
  }
}
