// Evaluation far from the data: the squared distance overflows (1e160² = inf) but a compactly
// supported kernel is exactly 0 there, so f is the polynomial part alone, not NaN.

#include <doctest/doctest.h>

#include <cmath>

#include "core/rbf/hrbf.h"
#include "support/test_data.h"

using namespace hermite;

TEST_CASE("far from a compact kernel's support f is the polynomial, in every evaluation path") {
  const HermiteSamples<3> s = testing::blob(30);
  for (const KernelType type : {KernelType::Wendland, KernelType::Gaussian, KernelType::InverseMultiquadric}) {
    CAPTURE(kernelName(type));
    const HrbfModel<3> model = fitHrbf<3>(s, {{type, 1.5}, Polynomial::Linear, 0.0, SolverChoice::Auto});
    Points<3> X(3, 3);
    X.col(0) = Vec<3>(1e160, -2e160, 3e159);
    X.col(1) = Vec<3>(-1e200, 0, 0);
    X.col(2) = Vec<3>(0.1, 0.2, 0.3);  // near the data: a normal point in the same batch
    Eigen::VectorXd f;
    Points<3> G;
    model.evaluateBatch(X, f, &G);
    const Eigen::VectorXd& c = model.poly();  // 1, x, y, z
    for (int i = 0; i < 2; ++i) {
      CAPTURE(i);
      REQUIRE(std::isfinite(f(i)));
      REQUIRE(G.col(i).allFinite());
      const double p = c(0) + c(1) * X(0, i) + c(2) * X(1, i) + c(3) * X(2, i);
      CHECK(f(i) == doctest::Approx(p).epsilon(1e-12));
      CHECK((G.col(i) - c.tail<3>()).norm() <= 1e-12 * c.tail<3>().norm());
      Vec<3> g;
      const double fi = model.evaluate(X.col(i), &g);
      CHECK(std::isfinite(fi));
      CHECK(fi == doctest::Approx(f(i)).epsilon(1e-12));
    }
    CHECK(std::isfinite(f(2)));
    CHECK(f(2) == doctest::Approx(model.evaluate(X.col(2))).epsilon(1e-9));
  }
}
