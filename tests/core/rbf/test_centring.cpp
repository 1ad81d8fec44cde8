// Data far from the origin (docs/maths.md, Centring): the polynomial is written about an exact
// centre, so a fit shifted by 1e12 has the residuals of the unshifted one.

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/base/exact_centre.h"
#include "core/rbf/hrbf.h"
#include "core/rbf/rbf_offset.h"
#include "core/rbf/similarity_transform.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

template <int Dim>
std::pair<double, double> residuals(const RadialSum<Dim>& model, const HermiteSamples<Dim>& s) {
  Eigen::VectorXd f;
  Points<Dim> G;
  model.evaluateBatch(s.points, f, &G);
  return {f.cwiseAbs().maxCoeff(), (G - s.normals).colwise().norm().maxCoeff()};
}

}  // namespace

TEST_CASE("exactCentre: zero near the origin, exact subtraction far from it") {
  const HermiteSamples<3> s = testing::blob(40);
  CHECK(exactCentre<3>(s.points).isZero());
  Points<3> shifted = s.points;
  shifted.row(0).array() += 0.75;  // still overlapping the origin's neighbourhood
  CHECK(exactCentre<3>(shifted).isZero());

  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), expo(0, 15);
  for (int trial = 0; trial < 200; ++trial) {
    const double offset = std::pow(10.0, expo(rng)) * unit(rng), extent = std::pow(10.0, -expo(rng) / 3);
    Points<3> P(3, 25);
    for (Eigen::Index i = 0; i < P.cols(); ++i)
      for (int k = 0; k < 3; ++k) P(k, i) = offset * (k + 1) + extent * unit(rng);
    const Vec<3> c = exactCentre<3>(P);
    for (Eigen::Index i = 0; i < P.cols(); ++i)
      for (int k = 0; k < 3; ++k) {
        CAPTURE(P(k, i));
        CAPTURE(c(k));
        REQUIRE((P(k, i) - c(k)) + c(k) == P(k, i));  // exact subtraction
      }
    // Far data is centred, unless rounding to the offset's ulp made all points one point.
    const double E = (P.rowwise().maxCoeff() - P.rowwise().minCoeff()).maxCoeff();
    CAPTURE(offset);
    CAPTURE(E);
    if (E > 0 && std::abs(offset) > 16 * E) CHECK_FALSE(c.isZero());
  }
}

TEST_CASE("a fit shifted by 1e12 keeps the residuals of the unshifted fit") {
  const HermiteSamples<3> base = testing::blob(40);
  const Vec<3> offset(1e12, -3e12, 2.5e12);
  HermiteSamples<3> far = base;
  far.points.colwise() += offset;
  // The shifted coordinates are rounded to multiples of ulp(3e12) ≈ 5e-4: `near` is that same
  // rounded data moved back (exactly) near the origin, so both fits see the same geometry.
  HermiteSamples<3> near = far;
  near.points.colwise() -= exactCentre<3>(far.points);
  for (const Polynomial poly : {Polynomial::Linear, Polynomial::Quadratic}) {
    CAPTURE(polynomialName(poly));
    const HrbfOptions o{{KernelType::Cubic, 1.0}, poly, 0.0, SolverChoice::Auto};
    const auto [fNear, gNear] = residuals<3>(fitHrbf<3>(near, o), near);
    const HrbfModel<3> farModel = fitHrbf<3>(far, o);
    CHECK_FALSE(farModel.polyOrigin().isZero());
    const auto [fFar, gFar] = residuals<3>(farModel, far);
    CAPTURE(fNear);
    CAPTURE(fFar);
    CHECK(fNear <= 1e-9);
    CHECK(fFar <= 10 * fNear + 1e-12);
    CHECK(gFar <= 10 * gNear + 1e-12);
    // The single-point path agrees with the batch.
    CHECK(std::abs(farModel.evaluate(far.points.col(3))) <= 10 * fNear + 1e-12);
  }
  const RbfOffsetOptions ro{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0, 0.01, SolverChoice::Auto};
  const auto [fNear, gNear] = residuals<3>(fitRbfOffset<3>(near, ro), near);
  const auto [fFar, gFar] = residuals<3>(fitRbfOffset<3>(far, ro), far);
  CHECK(fFar <= 10 * fNear + 1e-12);
}

TEST_CASE("a centred model moves with a similarity transform") {
  HermiteSamples<3> far = testing::blob(30);
  far.points.colwise() += Vec<3>(5e5, 0, -2e5);  // centred (|mid| ≫ extent), rounding still tiny
  const HrbfOptions o{{KernelType::Polyharmonic, 1.0}, Polynomial::Quadratic, 0.0, SolverChoice::Auto};
  const HrbfModel<3> model = fitHrbf<3>(far, o);
  REQUIRE_FALSE(model.polyOrigin().isZero());
  Similarity<3> T;
  T.q = 2.0;
  T.R = Eigen::AngleAxisd(0.3, Vec<3>(0, 0, 1)).toRotationMatrix();
  T.t = Vec<3>(-5e5, 1, 2e5);
  const HrbfModel<3> moved = transformModel<3>(model, T);
  // g(Tx) = q f(x) at points near the data.
  for (int i = 0; i < 5; ++i) {
    const Vec<3> x = far.points.col(i) + Vec<3>(0.05 * i, -0.03, 0.02);
    const double f = model.evaluate(x), g = moved.evaluate(T.apply(x));
    CHECK(g == doctest::Approx(T.q * f).epsilon(1e-6).scale(1.0));
  }
}
