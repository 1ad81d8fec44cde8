#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/base/errors.h"
#include "core/rbf/kernels.h"

using namespace hermite;

namespace {

std::vector<Kernel> testKernels() {
  std::vector<Kernel> ks;
  for (KernelType t : allKernelTypes())
    for (double r : {0.7, 1.3}) ks.push_back({t, r});
  return ks;
}

// Central difference of a scalar function with step h.
template <typename F>
double diff(F f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2 * h);
}

}  // namespace

TEST_CASE("kernel factors match finite differences, including next to a centre") {
  for (const Kernel& k : testKernels()) {
    CAPTURE(kernelName(k.type));
    CAPTURE(k.radius);
    for (double x : {1e-3, 0.01, 0.1, 0.3, 0.55, 0.9, 1.2, 2.0}) {
      CAPTURE(x);
      const double h = 1e-6 * std::max(x, 1e-3);
      const RadialTerms t = k.terms(x);
      auto phi = [&](double y) { return k.terms(y).phi; };
      auto dphi = [&](double y) { return k.terms(y).dphi; };
      auto e = [&](double y) { return k.terms(y).e; };
      const double scale = 1.0 + std::abs(t.phi) + std::abs(t.dphi);
      CHECK(std::abs(diff(phi, x, h) - t.dphi) <= 1e-7 * scale);
      CHECK(t.a == doctest::Approx(t.dphi / x).epsilon(1e-12));
      const double ddphi = diff(dphi, x, h);
      CHECK(std::abs(ddphi - t.ddphi()) <= 1e-6 * (1.0 + std::abs(ddphi)));
      CHECK(std::abs(t.e * x * x - t.b) <= 1e-12 * (1.0 + std::abs(t.b)));
      // e′ ~ g·x is small near 0: a larger step keeps rounding (ε·e/h) below the check.
      CHECK(std::abs(diff(e, x, 1e-3 * x) / x - t.g) <= 1e-5 * (1.0 + std::abs(t.g)));
    }
  }
}

TEST_CASE("kernel factors have the exact limits of docs/maths.md at a centre") {
  for (double r : {0.5, 2.0}) {
    const double r2 = r * r;
    CHECK(Kernel{KernelType::Gaussian, r}.terms(0).a == doctest::Approx(-2 / r2));
    CHECK(Kernel{KernelType::Wendland, r}.terms(0).a == doctest::Approx(-20 / r2));
    CHECK(Kernel{KernelType::Multiquadric, r}.terms(0).a == doctest::Approx(1 / r2));
    CHECK(Kernel{KernelType::InverseMultiquadric, r}.terms(0).a == doctest::Approx(-1 / r2));
  }
  CHECK(Kernel{KernelType::Cubic, 1}.terms(0).a == 0.0);
  CHECK(Kernel{KernelType::Polyharmonic, 1}.terms(0).a == 0.0);
  for (const Kernel& k : testKernels()) {
    const RadialTerms t = k.terms(0.0);
    CHECK(t.b == 0.0);
    CHECK(std::isfinite(t.phi));
    CHECK(std::isfinite(t.a));
    CHECK(std::isfinite(t.e));
    CHECK(std::isfinite(t.g));
    // a(x) → a(0) continuously.
    CHECK(std::abs(k.terms(1e-7).a - t.a) <= 1e-5 * (1 + std::abs(t.a)));
  }
}

TEST_CASE("3D gradient and Hessian of φ(‖d‖) from a and e match finite differences next to a centre") {
  for (const Kernel& k : testKernels()) {
    CAPTURE(kernelName(k.type));
    for (double len : {2e-3, 0.4}) {
      const Eigen::Vector3d d = len * Eigen::Vector3d(0.48, -0.6, 0.64);
      const RadialTerms t = k.terms(d.norm());
      const Eigen::Vector3d grad = t.a * d;
      const Eigen::Matrix3d H = t.a * Eigen::Matrix3d::Identity() + t.e * d * d.transpose();
      const double h = 1e-6;
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d dp = d, dm = d;
        dp(i) += h;
        dm(i) -= h;
        const RadialTerms tp = k.terms(dp.norm()), tm = k.terms(dm.norm());
        CHECK(std::abs((tp.phi - tm.phi) / (2 * h) - grad(i)) <= 1e-7 * (1 + grad.norm()));
        const Eigen::Vector3d col = (tp.a * dp - tm.a * dm) / (2 * h);
        CHECK((col - H.col(i)).norm() <= 1e-5 * (1 + H.norm()));
      }
    }
  }
}

TEST_CASE("radial bounds dominate |φ′| and the Hessian norm over an interval") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 3.0);
  for (const Kernel& k : testKernels()) {
    CAPTURE(kernelName(k.type));
    for (int trial = 0; trial < 50; ++trial) {
      double lo = u(rng), hi = u(rng);
      if (lo > hi) std::swap(lo, hi);
      const RadialBounds b = k.bounds(lo, hi);
      for (int s = 0; s <= 200; ++s) {
        const double x = lo + (hi - lo) * s / 200.0;
        const RadialTerms t = k.terms(x);
        CHECK(std::abs(t.dphi) <= b.dphi * (1 + 1e-12) + 1e-300);
        CHECK(std::max(std::abs(t.a), std::abs(t.ddphi())) <= b.hessian * (1 + 1e-12) + 1e-300);
      }
    }
  }
}

TEST_CASE("kernel properties: radius use, order, smoothing sign") {
  CHECK(Kernel{KernelType::Gaussian, 1}.usesRadius());
  CHECK_FALSE(Kernel{KernelType::Cubic, 1}.usesRadius());
  CHECK_FALSE(Kernel{KernelType::Polyharmonic, 1}.usesRadius());
  CHECK(Kernel{KernelType::Multiquadric, 1}.cpdOrder() == 1);
  CHECK(Kernel{KernelType::Cubic, 1}.cpdOrder() == 2);
  CHECK(Kernel{KernelType::Polyharmonic, 1}.cpdOrder() == 3);
  CHECK(Kernel{KernelType::Wendland, 1}.cpdOrder() == 0);
  CHECK(Kernel{KernelType::Multiquadric, 1}.smoothingSign() == -1);
  CHECK(Kernel{KernelType::Polyharmonic, 1}.smoothingSign() == -1);
  CHECK(Kernel{KernelType::Cubic, 1}.smoothingSign() == 1);
  CHECK(Kernel{KernelType::Wendland, 2}.phi(2.5) == 0.0);
}

TEST_CASE("kernel names parse; kernels that cannot carry Hermite data are rejected with the reason") {
  for (KernelType t : allKernelTypes()) CHECK(parseKernelType(kernelName(t)) == t);
  CHECK_THROWS_WITH_AS(parseKernelType("thin-plate"), doctest::Contains("no limit"), InputError);
  CHECK_THROWS_WITH_AS(parseKernelType("gausian"), doctest::Contains("expected one of"), InputError);
}
