#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/base/errors.h"
#include "core/points/normal_estimation.h"
#include "core/shapes/analytic_shapes.h"
#include "support/test_data.h"

using namespace hermite;

TEST_CASE("normal estimation: a sphere cloud gets outward unit normals") {
  const HermiteSamples<3> s = testing::goldenSphere(2000, 0.8);
  const Points<3> n = estimateNormals<3>(s.points);
  double worst = 1;
  for (int i = 0; i < s.size(); ++i) {
    CHECK(n.col(i).norm() == doctest::Approx(1.0).epsilon(1e-12));
    worst = std::min(worst, n.col(i).dot(s.normals.col(i)));
  }
  CHECK(worst > std::cos(5.0 * M_PI / 180));  // within 5° of the exact normal, all outward
}

TEST_CASE("normal estimation: a torus cloud and two separate components are oriented consistently") {
  // Area-uniform random torus points (R = 0.7, r = 0.3) and a far sphere: two components.
  const TorusField torus;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 2 * M_PI), v(0, 1);
  const int nt = 3000, ns = 500;
  Points<3> P(3, nt + ns), exact(3, nt + ns);
  for (int i = 0; i < nt;) {
    const double a = u(rng), b = u(rng);
    if (v(rng) > (0.7 + 0.3 * std::cos(b)) / 1.0) continue;
    const Vec<3> p((0.7 + 0.3 * std::cos(b)) * std::cos(a), (0.7 + 0.3 * std::cos(b)) * std::sin(a), 0.3 * std::sin(b));
    P.col(i) = p;
    exact.col(i) = torus.gradient(p).normalized();
    ++i;
  }
  const HermiteSamples<3> sphere = testing::goldenSphere(ns, 0.5);
  for (int i = 0; i < ns; ++i) {
    P.col(nt + i) = sphere.points.col(i) + Vec<3>(3, 0, 0);
    exact.col(nt + i) = sphere.normals.col(i);
  }
  const Points<3> n = estimateNormals<3>(P);
  int wrong = 0;
  double sumCos = 0;
  for (int i = 0; i < P.cols(); ++i) {
    const double c = n.col(i).dot(exact.col(i));
    if (c < 0) ++wrong;
    sumCos += c;
  }
  CHECK(wrong == 0);
  CHECK(sumCos / P.cols() > 0.99);
}

TEST_CASE("normal estimation: a 2D circle, flipping, and too few points") {
  const HermiteSamples<2> c = testing::ellipse(200, 1.0, 1.0);
  Points<2> n = estimateNormals<2>(c.points);
  for (int i = 0; i < c.size(); ++i) CHECK(n.col(i).dot(c.normals.col(i)) > 0.999);
  flipNormals<2>(n);
  for (int i = 0; i < c.size(); ++i) CHECK(n.col(i).dot(c.normals.col(i)) < -0.999);
  CHECK_THROWS_AS(estimateNormals<2>(Points<2>::Zero(2, 1)), InputError);
}
