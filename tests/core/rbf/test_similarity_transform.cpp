#include <doctest/doctest.h>

#include <random>

#include "core/rbf/similarity_transform.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

Similarity<3> similarity3(double q) {
  Similarity<3> T;
  T.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  T.t = Vec<3>(0.3, -1.2, 2.0);
  T.q = q;
  return T;
}

Similarity<2> similarity2(double q) {
  Similarity<2> T;
  const double a = 1.1;
  T.R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  T.t = Vec<2>(-0.4, 0.9);
  T.q = q;
  return T;
}

struct Config {
  Kernel kernel;
  Polynomial poly;
};

std::vector<Config> exactConfigs() {
  return {{{KernelType::Gaussian, 0.6}, Polynomial::None},         {{KernelType::Gaussian, 0.6}, Polynomial::Quadratic},
          {{KernelType::Wendland, 1.8}, Polynomial::Linear},       {{KernelType::Multiquadric, 0.8}, Polynomial::Linear},
          {{KernelType::InverseMultiquadric, 0.8}, Polynomial::None}, {{KernelType::Cubic, 1}, Polynomial::Linear},
          {{KernelType::Cubic, 1}, Polynomial::Quadratic},         {{KernelType::Polyharmonic, 1}, Polynomial::Quadratic}};
}

template <int Dim>
void checkSameField(const RadialSum<Dim>& a, const RadialSum<Dim>& b, const Points<Dim>& probes, double tol) {
  Eigen::VectorXd fa, fb;
  Points<Dim> ga, gb;
  a.evaluateBatch(probes, fa, &ga);
  b.evaluateBatch(probes, fb, &gb);
  const double scale = 1.0 + fb.cwiseAbs().maxCoeff();
  const double gscale = 1.0 + gb.colwise().norm().maxCoeff();
  CHECK((fa - fb).cwiseAbs().maxCoeff() <= tol * scale);
  CHECK((ga - gb).colwise().norm().maxCoeff() <= tol * gscale);
}

template <int Dim>
Points<Dim> randomProbes(const Points<Dim>& around, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Points<Dim> X(Dim, n);
  const Vec<Dim> c = around.rowwise().mean();
  const double s = (around.colwise() - c).colwise().norm().maxCoeff() * 1.3;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < Dim; ++k) X(k, i) = c(k) + s * u(rng);
  return X;
}

}  // namespace

TEST_CASE("coefficient updates equal the re-solved fit of the transformed data (3D, every kernel)") {
  const HermiteSamples<3> s = testing::blob(30);
  for (double q : {0.5, 1.0, 2.5}) {
    const Similarity<3> T = similarity3(q);
    const HermiteSamples<3> moved = transformSamples(s, T);
    for (const Config& c : exactConfigs()) {
      CAPTURE(kernelName(c.kernel.type));
      CAPTURE(polynomialName(c.poly));
      CAPTURE(q);
      REQUIRE(coefficientUpdateIsExact(c.kernel, c.poly, 0.0, nullptr));
      const HrbfModel<3> m = fitHrbf<3>(s, {c.kernel, c.poly, 0.0});
      const HrbfModel<3> updated = transformModel<3>(m, T);
      Kernel k2 = c.kernel;
      if (k2.usesRadius()) k2.radius *= q;
      const HrbfModel<3> resolved = fitHrbf<3>(moved, {k2, c.poly, 0.0});
      // Coefficients too: the interpolant is unique.
      const double as = resolved.alpha().cwiseAbs().maxCoeff(), bs = resolved.beta().cwiseAbs().maxCoeff();
      CHECK((updated.alpha() - resolved.alpha()).cwiseAbs().maxCoeff() <= 1e-8 * as);
      CHECK((updated.beta() - resolved.beta()).cwiseAbs().maxCoeff() <= 1e-8 * bs);
      checkSameField<3>(updated, resolved, randomProbes<3>(moved.points, 100, 3), 1e-9);
      // And g(x) = q f(T⁻¹x) at random points.
      const Points<3> X = randomProbes<3>(moved.points, 20, 4);
      for (int i = 0; i < X.cols(); ++i) {
        const Vec<3> x = X.col(i);
        CHECK(std::abs(updated.value(x) - q * m.value(T.applyInverse(x))) <= 1e-9 * (1 + std::abs(updated.value(x))));
      }
    }
  }
}

TEST_CASE("coefficient updates equal the re-solve in 2D and for RBF-offset") {
  const HermiteSamples<2> s = testing::ellipse(20);
  const Similarity<2> T = similarity2(1.7);
  const HermiteSamples<2> moved = transformSamples(s, T);
  for (const Config& c : exactConfigs()) {
    CAPTURE(kernelName(c.kernel.type));
    Kernel k2 = c.kernel;
    if (k2.usesRadius()) k2.radius *= T.q;
    const HrbfModel<2> updated = transformModel<2>(fitHrbf<2>(s, {c.kernel, c.poly, 0.0}), T);
    const HrbfModel<2> resolved = fitHrbf<2>(moved, {k2, c.poly, 0.0});
    checkSameField<2>(updated, resolved, randomProbes<2>(moved.points, 100, 5), 1e-9);

    // Both fits lose digits in proportion to the condition number: the tolerance follows it.
    FitReport rep;
    const RbfOffsetModel<2> ro = fitRbfOffset<2>(s, {c.kernel, c.poly, 0.0, 0.1}, &rep);
    const RbfOffsetModel<2> roUpdated = transformModel<2>(ro, T);
    const RbfOffsetModel<2> roResolved = fitRbfOffset<2>(moved, {k2, c.poly, 0.0, 0.1 * T.q});
    CHECK(roUpdated.shift() == doctest::Approx(0.1 * T.q));
    CAPTURE(rep.conditionEstimate);
    checkSameField<2>(roUpdated, roResolved, randomProbes<2>(moved.points, 100, 6),
                      std::max(1e-9, 1e-15 * rep.conditionEstimate));
  }
}

TEST_CASE("the polynomial is re-expressed exactly: q·p(T⁻¹x)") {
  const Similarity<3> T = similarity3(1.9);
  Eigen::VectorXd c(10);
  c << 0.3, -1.0, 0.5, 2.0, 0.7, -0.2, 0.4, 1.1, -0.6, 0.25;
  const Eigen::VectorXd c2 = transformPolynomial<3>(Polynomial::Quadratic, c, T);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 20; ++i) {
    const Vec<3> x(u(rng), u(rng), u(rng));
    const double expected = T.q * evaluatePolynomial<3>(Polynomial::Quadratic, c, T.applyInverse(x), nullptr, nullptr);
    CHECK(evaluatePolynomial<3>(Polynomial::Quadratic, c2, x, nullptr, nullptr) == doctest::Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("outside the exact conditions the update is flagged (and still equals q·f(T⁻¹x))") {
  std::string why;
  CHECK_FALSE(coefficientUpdateIsExact({KernelType::Cubic, 1}, Polynomial::Linear, 0.1, &why));
  CHECK(why.find("smoothing") != std::string::npos);
  CHECK_FALSE(coefficientUpdateIsExact({KernelType::Cubic, 1}, Polynomial::None, 0.0, &why));
  CHECK(why.find("below the order") != std::string::npos);
  CHECK_FALSE(coefficientUpdateIsExact({KernelType::Polyharmonic, 1}, Polynomial::Linear, 0.0, &why));
  CHECK(coefficientUpdateIsExact({KernelType::Gaussian, 1}, Polynomial::None, 0.0, &why));

  const HermiteSamples<3> s = testing::blob(20);
  const Similarity<3> T = similarity3(2.0);
  const HrbfModel<3> m = fitHrbf<3>(s, {{KernelType::Cubic, 1}, Polynomial::Linear, 0.1});
  const HrbfModel<3> g = transformModel<3>(m, T);
  const Vec<3> x(0.2, -0.4, 1.5);
  CHECK(g.value(x) == doctest::Approx(T.q * m.value(T.applyInverse(x))).epsilon(1e-10));
}
