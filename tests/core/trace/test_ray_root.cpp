#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <optional>

#include "core/shapes/analytic_shapes.h"
#include "core/trace/ray_root.h"

using namespace hermite;

namespace {

// f(x) = g(x₀): a field that varies along x only, so along the ray from the origin in +x
// f(ray.at(t)) = g(t).
template <class G>
class AlongX final : public ImplicitField<3> {
 public:
  explicit AlongX(G g) : g_(g) {}
  double evaluate(const Vec<3>& x, Vec<3>* grad, Mat<3>* H) const override {
    ++evaluations;
    if (grad) *grad = Vec<3>::UnitX();
    if (H) H->setZero();
    return g_(x.x());
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }
  mutable int evaluations = 0;

 private:
  G g_;
};

const Ray kAlongX{Vec<3>::Zero(), Vec<3>::UnitX()};

RayRootOptions options(double tolerance, int samples, ZeroRule rule = ZeroRule::ZeroIsPast) {
  RayRootOptions o;
  o.tolerance = tolerance;
  o.samples = samples;
  o.rule = rule;
  return o;
}

}  // namespace

TEST_CASE("ray root: finds where a ray enters a sphere to the tolerance, under both rules") {
  const SphereField sphere(Vec<3>(0.1, 0.2, -0.1), 0.8);
  const Ray ray{Vec<3>(0, 0, 4), Vec<3>(0.02, 0.05, -1).normalized()};
  // The analytic entry: t² + 2b·t + q = 0 with b = (o − c)·d, q = ‖o − c‖² − R².
  const Vec<3> oc = ray.origin - sphere.centre();
  const double b = oc.dot(ray.direction), q = oc.squaredNorm() - 0.64;
  const double entry = -b - std::sqrt(b * b - q);
  for (ZeroRule rule : {ZeroRule::StopAtZero, ZeroRule::ZeroIsPast}) {
    const std::optional<double> t = refineRayRoot(sphere, ray, 2.0, 6.0, options(1e-9, 16, rule));
    REQUIRE(t.has_value());
    CHECK(std::abs(*t - entry) <= 1e-9);
    CHECK(std::abs(sphere.value(ray.at(*t))) <= 1e-9);  // a distance field: |f| is the distance
  }
}

TEST_CASE("ray root: the first sign change inside the bracket, never a root outside it") {
  // Roots at t = 1, 2, 3 and 4; f > 0 on (1, 2) and (3, 4).
  const AlongX field([](double t) { return -(t - 1) * (t - 2) * (t - 3) * (t - 4); });
  // [1.6, 3.5]: the only roots inside are 2 and 3, and 2 comes first.
  const std::optional<double> t = refineRayRoot(field, kAlongX, 1.6, 3.5, options(1e-10, 8));
  REQUIRE(t.has_value());
  CHECK(std::abs(*t - 2.0) <= 1e-10);
  // [2.2, 2.8] holds no root (f < 0 throughout), although roots lie just outside it.
  CHECK_FALSE(refineRayRoot(field, kAlongX, 2.2, 2.8, options(1e-10, 8)).has_value());
}

TEST_CASE("ray root: no root where f keeps one sign, and f = 0 at the start is the root") {
  const SphereField sphere(Vec<3>::Zero(), 1.0);
  const Ray ray{Vec<3>(0, 0, 4), Vec<3>(0, 0, -1)};
  CHECK_FALSE(refineRayRoot(sphere, ray, 0.0, 2.5, options(1e-9, 16)).has_value());  // outside all the way
  const Ray past{Vec<3>(0, 3, 4), Vec<3>(0, 0, -1)};
  CHECK_FALSE(refineRayRoot(sphere, past, 0.0, 8.0, options(1e-9, 16)).has_value());  // misses the sphere
  const AlongX field([](double t) { return t - 0.25; });
  CHECK(refineRayRoot(field, kAlongX, 0.25, 1.0, options(1e-9, 4)) == 0.25);
}

TEST_CASE("ray root: the rules differ only on a probe where f is exactly 0") {
  // f = 0 on [0.4, 0.6], negative before and positive after; probes at 0.25, 0.5, 0.75, 1.
  const AlongX field([](double t) { return t < 0.4 ? t - 0.4 : t > 0.6 ? t - 0.6 : 0.0; });
  // StopAtZero takes the probe at 0.5 as the root; ZeroIsPast bisects to the stretch's start.
  CHECK(refineRayRoot(field, kAlongX, 0.0, 1.0, options(1e-9, 4, ZeroRule::StopAtZero)) == 0.5);
  const std::optional<double> first = refineRayRoot(field, kAlongX, 0.0, 1.0, options(1e-9, 4, ZeroRule::ZeroIsPast));
  REQUIRE(first.has_value());
  CHECK(std::abs(*first - 0.4) <= 1e-9);
  // Without a zero at a probe both rules give the same bits.
  const AlongX line([](double t) { return t - 0.3; });
  CHECK(refineRayRoot(line, kAlongX, 0.0, 1.0, options(1e-9, 4, ZeroRule::StopAtZero)) ==
        refineRayRoot(line, kAlongX, 0.0, 1.0, options(1e-9, 4, ZeroRule::ZeroIsPast)));
}

TEST_CASE("ray root: a NaN opens no bracket under StopAtZero and reads as positive under ZeroIsPast") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(judgeProbe(-1.0, nan, ZeroRule::StopAtZero) == ProbeVerdict::NoChange);
  CHECK(judgeProbe(-1.0, nan, ZeroRule::ZeroIsPast) == ProbeVerdict::SignChange);
  CHECK(judgeProbe(1.0, nan, ZeroRule::ZeroIsPast) == ProbeVerdict::NoChange);
  // Inside a bracket from f(lo) > 0: StopAtZero moves hi to the NaN probe, ZeroIsPast moves lo.
  RootBracket stop(0.0, 1.0, 1.0, ZeroRule::StopAtZero), past(0.0, 1.0, 1.0, ZeroRule::ZeroIsPast);
  CHECK_FALSE(stop.narrow(nan));
  CHECK_FALSE(past.narrow(nan));
  CHECK(stop.hi() == 0.5);
  CHECK(past.lo() == 0.5);
}

TEST_CASE("ray root: bisection halves the bracket per probe and stops at neighbouring doubles") {
  const AlongX field([](double t) { return t - 1.0 / 3.0; });
  // Tolerance 2⁻²⁰ over [0, 1] with 4 samples: 4 probes to find [0.25, 0.5], then 18 halvings.
  field.evaluations = 0;
  const std::optional<double> t = refineRayRoot(field, kAlongX, 0.0, 1.0, options(std::ldexp(1.0, -20), 4));
  REQUIRE(t.has_value());
  CHECK(std::abs(*t - 1.0 / 3.0) <= std::ldexp(1.0, -21));
  CHECK(field.evaluations == 1 + 2 + 18);
  // Tolerance 0: bisection ends when no double lies between the bracket's ends.
  const std::optional<double> exact = refineRayRoot(field, kAlongX, 0.0, 1.0, options(0.0, 4));
  REQUIRE(exact.has_value());
  CHECK(std::abs(*exact - 1.0 / 3.0) <= 2 * std::numeric_limits<double>::epsilon());
}
