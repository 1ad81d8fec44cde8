// The zero-set check and the degenerate-field detection (docs/maths.md, "Suggesting r",
// "Degenerate fields") on fields whose answers are known in closed form.

#include <doctest/doctest.h>

#include <cmath>

#include "core/mesh/degenerate_field.h"
#include "core/mesh/flat_masked_field.h"
#include "core/mesh/marching_squares.h"
#include "core/mesh/zero_set_check.h"

using namespace hermite;

namespace {

// Signed distance to circles of radius ρ about `centres` (the nearest circle wins): the zero set
// is the circles, ∇f = unit outward.
class Circles final : public ImplicitField<2> {
 public:
  Circles(std::vector<Vec<2>> centres, double rho) : c_(std::move(centres)), rho_(rho) {}
  double evaluate(const Vec<2>& x, Vec<2>* g, Mat<2>* H) const override {
    std::size_t k = 0;
    for (std::size_t i = 1; i < c_.size(); ++i)
      if ((x - c_[i]).norm() < (x - c_[k]).norm()) k = i;
    const Vec<2> d = x - c_[k];
    if (g) *g = d / std::max(d.norm(), 1e-300);
    if (H) H->setZero();
    return d.norm() - rho_;
  }
  double lipschitzBound(const Box<2>&) const override { return 1; }

 private:
  std::vector<Vec<2>> c_;
  double rho_;
};

// f = s·(‖x‖ − 1) inside the disc of radius 1.5, exactly 0 beyond (a compact kernel's field far
// from its data): flat outside radius 1.5.
class CompactDisc final : public ImplicitField<2> {
 public:
  double evaluate(const Vec<2>& x, Vec<2>* g, Mat<2>* H) const override {
    const double r = x.norm();
    if (H) H->setZero();
    if (r >= 1.5) {
      if (g) g->setZero();
      return 0;
    }
    if (g) *g = x / std::max(r, 1e-300);
    return r - 1;
  }
  double lipschitzBound(const Box<2>&) const override { return 1; }
};

// n samples on the unit circle with outward normals.
HermiteSamples<2> unitCircle(int n) {
  HermiteSamples<2> s;
  s.points.resize(2, n);
  for (int i = 0; i < n; ++i) s.points.col(i) = Vec<2>(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n));
  s.normals = s.points;
  return s;
}

Box<2> square(double h) {
  Box<2> b;
  b.lo = Vec<2>(-h, -h);
  b.hi = Vec<2>(h, h);
  return b;
}

}  // namespace

TEST_CASE("zero-set check: one circle through the samples is one supported component, no sign failure") {
  const HermiteSamples<2> s = unitCircle(24);
  const ZeroSetCheck z = checkZeroSet<2>(Circles({Vec<2>(0, 0)}, 1.0), square(2), s);
  CHECK(z.components == 1);
  CHECK(z.spurious == 0);
  CHECK(z.signFailures == 0);
  CHECK_FALSE(z.degenerate.degenerate);
  CHECK(z.pushDistance == doctest::Approx(0.25 * meanSampleSpacing<2>(s.points)).epsilon(1e-12));
}

TEST_CASE("zero-set check: a loop far from every sample is spurious; samples on the wrong side fail the sign test") {
  const HermiteSamples<2> s = unitCircle(24);
  // The unit circle plus a small loop at (1.7, 1.7): two components, the second near no sample.
  const ZeroSetCheck z = checkZeroSet<2>(Circles({Vec<2>(0, 0), Vec<2>(1.7, 1.7)}, 1.0 * 0.999), square(2.2), s);
  CHECK(z.components == 2);
  CHECK(z.spurious == 1);
  // Normals turned inward: every sample's pushed points have the wrong signs.
  HermiteSamples<2> flipped = s;
  flipped.normals = -s.normals;
  CHECK(checkZeroSet<2>(Circles({Vec<2>(0, 0)}, 1.0), square(2), flipped).signFailures == 24);
}

TEST_CASE("degenerate field: flat beyond the support is detected, the flat region is masked as no data") {
  const HermiteSamples<2> s = unitCircle(24);
  const CompactDisc disc;
  // Box ±1.5: flat only in the corners (|x| ≥ 1.5): 1 − π·1.5²/3² ≈ 21 % — not degenerate.
  const DegenerateFieldReport small = detectDegenerateField<2>(disc, square(1.5), s);
  CHECK(small.flatFraction == doctest::Approx(1 - M_PI * 2.25 / 9).epsilon(0.03));
  CHECK_FALSE(small.degenerate);
  CHECK(small.message().empty());
  // Box ±3: 1 − π·1.5²/36 ≈ 80 % flat — degenerate, with cause and remedy.
  const DegenerateFieldReport large = detectDegenerateField<2>(disc, square(3), s);
  CHECK(large.flatFraction == doctest::Approx(1 - M_PI * 2.25 / 36).epsilon(0.03));
  CHECK(large.degenerate);
  CHECK(large.message().rfind(kDegenerateFieldWarningStart, 0) == 0);
  CHECK(large.message().find("add a polynomial or increase r") != std::string::npos);
  CHECK(large.scale.gradient == doctest::Approx(1.0));

  // Masked: f unchanged, no data where flat, the real zero set (the unit circle) kept whole.
  const FlatMaskedField<2> masked(disc, large.scale);
  CHECK(masked.value(Vec<2>(2, 2)) == 0.0);
  CHECK_FALSE(masked.valid(Vec<2>(2, 2)));
  CHECK(masked.valid(Vec<2>(1, 0)));
  CHECK(masked.valid(Vec<2>(0.2, 0.1)));
  const std::vector<Polyline2d> lines = marchingSquares(masked, square(3), {});
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].closed);
}

TEST_CASE("degenerate field: a field that is exactly zero inside the shape grows a false surface; the mask removes it") {
  // f = 0 for ‖x‖ < 0.5 (no kernel reaches the centre), ‖x‖ − 1 elsewhere, flat beyond 1.5 too:
  // f ≥ 0 counts as outside, so the contour has the unit circle and the circle of radius 0.5.
  class Hollow final : public ImplicitField<2> {
   public:
    double evaluate(const Vec<2>& x, Vec<2>* g, Mat<2>* H) const override {
      const double r = x.norm();
      if (H) H->setZero();
      if (r < 0.5 || r >= 1.5) {
        if (g) g->setZero();
        return 0;
      }
      if (g) *g = x / r;
      return r - 1;
    }
    double lipschitzBound(const Box<2>&) const override { return 1; }
  } hollow;
  const HermiteSamples<2> s = unitCircle(24);
  CHECK(marchingSquares(hollow, square(3), {}).size() == 2);
  const DegenerateFieldReport rep = detectDegenerateField<2>(hollow, square(3), s);
  REQUIRE(rep.degenerate);
  const std::vector<Polyline2d> masked = marchingSquares(FlatMaskedField<2>(hollow, rep.scale), square(3), {});
  // What is left is the unit circle; the inner "surface" of noise is gone.
  REQUIRE(masked.size() == 1);
  CHECK(masked[0].closed);
  for (Eigen::Index k = 0; k < masked[0].points.cols(); ++k) CHECK(masked[0].points.col(k).norm() == doctest::Approx(1.0).epsilon(0.01));
}
