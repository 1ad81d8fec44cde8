#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/base/errors.h"
#include "core/shapes/analytic_shapes.h"

using namespace hermite;

namespace {

// Central differences with step h: gradient error O(h²·f‴) + O(ε/h); the Hessian is
// differenced from the exact gradient. With h = 1e-5 on fields whose third derivatives are
// O(1/distance²) away from the singular sets (kept ≥ 0.05 away below), 1e-6 is a safe bound.
constexpr double kStep = 1e-5;
constexpr double kTolerance = 1e-6;

template <int Dim>
void checkDerivatives(const ImplicitField<Dim>& field, const Vec<Dim>& x) {
  CAPTURE(x.transpose());
  Vec<Dim> g;
  Mat<Dim> H;
  const double f = field.evaluate(x, &g, &H);
  CHECK(f == field.evaluate(x));
  CHECK(g == field.gradient(x));
  for (int k = 0; k < Dim; ++k) {
    const Vec<Dim> e = kStep * Vec<Dim>::Unit(k);
    const double fd = (field.evaluate(x + e) - field.evaluate(x - e)) / (2 * kStep);
    CHECK(std::abs(fd - g(k)) <= kTolerance);
    const Vec<Dim> hd = (field.gradient(x + e) - field.gradient(x - e)) / (2 * kStep);
    CHECK((hd - H.col(k)).cwiseAbs().maxCoeff() <= kTolerance);
  }
  CHECK((H - H.transpose()).cwiseAbs().maxCoeff() <= 1e-12);
  // A distance field has a unit gradient wherever it is differentiable.
  CHECK(std::abs(g.norm() - 1.0) <= 1e-12);
}

template <int Dim>
Vec<Dim> randomPoint(std::mt19937& rng, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  Vec<Dim> x;
  for (int k = 0; k < Dim; ++k) x(k) = u(rng);
  return x;
}

template <int Dim>
void checkFinite(const ImplicitField<Dim>& field, const Vec<Dim>& x) {
  CAPTURE(x.transpose());
  Vec<Dim> g;
  Mat<Dim> H;
  const double f = field.evaluate(x, &g, &H);
  CHECK(std::isfinite(f));
  CHECK(g.allFinite());
  CHECK(H.allFinite());
}

// |f(x) − f(y)| ≤ L‖x − y‖ for random pairs in the box, and ‖∇f‖ ≤ L at random points.
template <int Dim>
void checkLipschitz(const ImplicitField<Dim>& field, std::mt19937& rng) {
  Box<Dim> box;
  box.lo = Vec<Dim>::Constant(-1.5);
  box.hi = Vec<Dim>::Constant(1.5);
  const double L = field.lipschitzBound(box);
  CHECK(L == 1.0);
  for (int i = 0; i < 2000; ++i) {
    const Vec<Dim> x = randomPoint<Dim>(rng, 1.5);
    const Vec<Dim> y = randomPoint<Dim>(rng, 1.5);
    CHECK(std::abs(field.value(x) - field.value(y)) <= L * (x - y).norm() * (1 + 1e-12) + 1e-15);
    CHECK(field.gradient(x).norm() <= L * (1 + 1e-12));
  }
}

}  // namespace

TEST_CASE("analytic shapes: circle and sphere derivatives match central differences") {
  std::mt19937 rng(20240601);
  const CircleField circle(Vec<2>(0.2, -0.1), 0.8);
  const SphereField sphere(Vec<3>(0.1, 0.2, -0.3), 0.9);
  for (int i = 0; i < 200; ++i) {
    const Vec<2> x2 = randomPoint<2>(rng, 1.5);
    if ((x2 - circle.centre()).norm() > 0.05) checkDerivatives(circle, x2);
    const Vec<3> x3 = randomPoint<3>(rng, 1.5);
    if ((x3 - sphere.centre()).norm() > 0.05) checkDerivatives(sphere, x3);
  }
  CHECK(circle.value(Vec<2>(1.0, -0.1)) == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(circle.gradient(Vec<2>(1.0, -0.1)).isApprox(Vec<2>(1, 0), 1e-15));
  CHECK(sphere.value(sphere.centre() + Vec<3>(0, 0.9, 0)) == doctest::Approx(0.0).epsilon(1e-15));
}

TEST_CASE("analytic shapes: torus derivatives match central differences, any axis") {
  std::mt19937 rng(7);
  const TorusField torus;  // R = 0.7, r = 0.3 about z
  CHECK(torus.majorRadius() == 0.7);
  CHECK(torus.minorRadius() == 0.3);
  CHECK(torus.value(Vec<3>(1.0, 0, 0)) == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(torus.value(Vec<3>(0, 0.4, 0)) == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(torus.value(Vec<3>(0, 0.7, 0.3)) == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(torus.gradient(Vec<3>(0, 0.7, 0.3)).isApprox(Vec<3>(0, 0, 1), 1e-15));
  CHECK(torus.gradient(Vec<3>(0, 0.4, 0)).isApprox(Vec<3>(0, -1, 0), 1e-15));

  const Vec<3> centre(0.1, -0.2, 0.05);
  const Vec<3> axis = Vec<3>(1, 2, -0.5).normalized();
  const TorusField tilted(centre, 0.6, 0.25, 3.0 * axis);
  CHECK(tilted.axis().isApprox(axis, 1e-15));
  // The tilted torus is the z torus seen through the rotation Q (z ↦ axis).
  const Mat<3> Q = Eigen::Quaterniond::FromTwoVectors(Vec<3>::UnitZ(), axis).toRotationMatrix();
  const TorusField reference(Vec<3>::Zero(), 0.6, 0.25);

  for (int i = 0; i < 300; ++i) {
    const Vec<3> x = randomPoint<3>(rng, 1.5);
    const double q = x.head<2>().norm();
    const double core = std::hypot(q - 0.7, x.z());
    if (q > 0.05 && core > 0.05) checkDerivatives(torus, x);

    const Vec<3> y = randomPoint<3>(rng, 1.2);
    const double qy = y.head<2>().norm();
    if (qy > 0.05 && std::hypot(qy - 0.6, y.z()) > 0.05) {
      const Vec<3> xt = centre + Q * y;
      checkDerivatives(tilted, xt);
      Vec<3> g;
      Mat<3> H;
      Vec<3> gRef;
      Mat<3> HRef;
      CHECK(std::abs(tilted.evaluate(xt, &g, &H) - reference.evaluate(y, &gRef, &HRef)) <= 1e-14);
      CHECK((g - Q * gRef).norm() <= 1e-13);
      CHECK((H - Q * HRef * Q.transpose()).cwiseAbs().maxCoeff() <= 1e-11 * (1 + HRef.norm()));
    }
  }
}

TEST_CASE("analytic shapes: no NaN at the centre, on the axis or on the core circle") {
  const CircleField circle(Vec<2>(0.3, 0.4), 0.5);
  checkFinite(circle, circle.centre());
  CHECK(circle.value(circle.centre()) == -0.5);
  CHECK(circle.gradient(circle.centre()).norm() == 0.0);
  checkFinite(circle, Vec<2>(circle.centre() + Vec<2>(1e-300, 0)));

  const SphereField sphere;
  checkFinite(sphere, Vec<3>(Vec<3>::Zero()));
  CHECK(sphere.value(Vec<3>::Zero()) == -1.0);
  CHECK(sphere.hessian(Vec<3>::Zero()).norm() == 0.0);
  checkFinite(sphere, Vec<3>(1e-160, -1e-170, 1e-200));
  checkFinite(sphere, Vec<3>(1e-140, 0, 0));

  const TorusField torus;
  // Axis: a ridge. Subgradient h/D·a, Hessian the exact second derivative along the axis.
  for (double h : {0.0, 0.5, -2.0}) {
    const Vec<3> x(0, 0, h);
    checkFinite(torus, x);
    const double D = std::hypot(0.7, h);
    CHECK(torus.value(x) == doctest::Approx(D - 0.3).epsilon(1e-15));
    CHECK(torus.gradient(x).isApprox(Vec<3>(0, 0, h / D), 1e-15));
    const Mat<3> H = torus.hessian(x);
    CHECK(H(2, 2) == doctest::Approx(0.49 / (D * D * D)).epsilon(1e-14));
    CHECK(H.topLeftCorner<2, 2>().norm() == 0.0);
  }
  checkFinite(torus, Vec<3>(1e-200, 0, 0.1));
  // Core circle: the minimum, f = −r, gradient and Hessian 0.
  checkFinite(torus, Vec<3>(0.7, 0, 0));
  CHECK(torus.value(Vec<3>(0.7, 0, 0)) == -0.3);
  CHECK(torus.gradient(Vec<3>(0.7, 0, 0)).norm() == 0.0);
  CHECK(torus.hessian(Vec<3>(0.7, 0, 0)).norm() == 0.0);
  for (double angle : {1.0, 4.0}) {
    const Vec<3> x(0.7 * std::cos(angle), 0.7 * std::sin(angle), 0);
    checkFinite(torus, x);
    CHECK(torus.value(x) == doctest::Approx(-0.3).epsilon(1e-15));
    CHECK(torus.gradient(x).norm() <= 1.0 + 1e-15);
  }
  checkFinite(torus, Vec<3>(0.7, 0, 1e-160));
  checkFinite(torus, Vec<3>(0.7, 0, 1e-140));
  checkFinite(torus, torus.centre());
}

TEST_CASE("analytic shapes: Lipschitz bound 1 holds on random pairs") {
  std::mt19937 rng(12345);
  checkLipschitz<2>(CircleField(Vec<2>(0.1, 0.2), 0.6), rng);
  checkLipschitz<3>(SphereField(), rng);
  checkLipschitz<3>(TorusField(), rng);
  checkLipschitz<3>(TorusField(Vec<3>(0.2, 0, 0), 0.5, 0.2, Vec<3>(0, 1, 1)), rng);
}

TEST_CASE("analytic shapes: factories and invalid parameters") {
  const auto sphere = makeAnalyticField3d("sphere");
  CHECK(sphere->value(Vec<3>(0, 0, 1)) == 0.0);
  const auto torus = makeAnalyticField3d("torus");
  CHECK(torus->value(Vec<3>(1, 0, 0)) == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(torus->value(Vec<3>(0.7, 0, 0)) == doctest::Approx(-0.3).epsilon(1e-15));
  const auto circle = makeAnalyticField2d("circle");
  CHECK(circle->value(Vec<2>(0, -1)) == 0.0);
  CHECK_THROWS_AS(makeAnalyticField3d("teapot"), InputError);
  CHECK_THROWS_AS(makeAnalyticField2d("sphere"), InputError);
  CHECK_THROWS_AS(SphereField(Vec<3>::Zero(), 0.0), InputError);
  CHECK_THROWS_AS(CircleField(Vec<2>::Zero(), -1.0), InputError);
  CHECK_THROWS_AS(SphereField(Vec<3>(NAN, 0, 0), 1.0), InputError);
  CHECK_THROWS_AS(TorusField(Vec<3>::Zero(), 0.0, 0.3), InputError);
  CHECK_THROWS_AS(TorusField(Vec<3>::Zero(), 0.7, INFINITY), InputError);
  CHECK_THROWS_AS(TorusField(Vec<3>::Zero(), 0.7, 0.3, Vec<3>::Zero()), InputError);
}
