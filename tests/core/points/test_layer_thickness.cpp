// The thickness of a cloud's layer (layer_thickness.h): sampled surfaces and curves are thin,
// clouds whose noise is as large as their spacing are not.

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/points/layer_thickness.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// `points` moved by Gaussian noise of standard deviation sigma along every axis (seeded).
template <int Dim>
Points<Dim> noisy(Points<Dim> points, double sigma) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, sigma);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] += gauss(rng);
  return points;
}

Points<2> circle(int n) {
  Points<2> p(2, n);
  for (int i = 0; i < n; ++i) p.col(i) = Vec<2>(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n));
  return p;
}

}  // namespace

TEST_CASE("layer thickness: a sampled sphere is thin, the same points moved by noise of a spacing or more are not") {
  const Points<3> sphere = testing::goldenSphere(20000).points;
  const double spacing = std::sqrt(4 * M_PI / 20000);  // about 0.025
  const LayerThickness clean = layerThickness<3>(sphere);
  CAPTURE(clean.median);
  CHECK(clean.probes >= 1000);
  CHECK(clean.median < 0.05);
  const double slight = layerThickness<3>(noisy<3>(sphere, 0.1 * spacing)).median;
  CAPTURE(slight);
  CHECK(slight < kNoisyLayer);  // a tenth of a spacing: a scan's usual noise, not flagged
  const double heavy = layerThickness<3>(noisy<3>(sphere, 1.5 * spacing)).median;
  CAPTURE(heavy);
  CHECK(heavy >= kNoisyLayer);
  // Above maxTree points the neighbours come from a strided subset: the verdicts stay.
  LayerThicknessOptions few;
  few.maxTree = 5000;
  CHECK(layerThickness<3>(sphere, few).median < 0.1);
  CHECK(layerThickness<3>(noisy<3>(sphere, 3 * spacing), few).median >= kNoisyLayer);
}

TEST_CASE("layer thickness: a sampled circle is thin, a noisy one is not; too few points give 0") {
  const Points<2> c = circle(4000);
  const double spacing = 2 * M_PI / 4000;
  CHECK(layerThickness<2>(c).median < 0.05);
  CHECK(layerThickness<2>(noisy<2>(c, 2 * spacing)).median >= kNoisyLayer);
  const LayerThickness tiny = layerThickness<3>(testing::goldenSphere(8).points);
  CHECK(tiny.median == 0);
  CHECK(tiny.probes == 0);
}
