#include <doctest/doctest.h>

#include "core/rbf/rbf_offset.h"
#include "support/test_data.h"

using namespace hermite;

TEST_CASE("RBF-offset interpolates 0 at the samples and ±δ at the offset points") {
  const HermiteSamples<3> s3 = testing::blob(30);
  const HermiteSamples<2> s2 = testing::ellipse(20);
  for (const Kernel k : {Kernel{KernelType::Gaussian, 0.5}, Kernel{KernelType::Cubic, 1}, Kernel{KernelType::Polyharmonic, 1}}) {
    CAPTURE(kernelName(k.type));
    const Polynomial p = k.type == KernelType::Polyharmonic ? Polynomial::Quadratic : Polynomial::Linear;
    const double delta = 0.05;
    FitReport rep;
    const RbfOffsetModel<3> m = fitRbfOffset<3>(s3, {k, p, 0.0, delta}, &rep);
    CHECK(rep.nUnknowns == 3 * s3.size() + monomialCount<3>(p));
    CHECK_FALSE(m.hasBeta());
    for (int i = 0; i < s3.size(); ++i) {
      const Vec<3> x = s3.points.col(i), n = s3.normals.col(i);
      CHECK(std::abs(m.value(x)) <= 1e-9);
      CHECK(std::abs(m.value(x + delta * n) - delta) <= 1e-9);
      CHECK(std::abs(m.value(x - delta * n) + delta) <= 1e-9);
    }
    const RbfOffsetModel<2> m2 = fitRbfOffset<2>(s2, {k, p, 0.0, delta});
    for (int i = 0; i < s2.size(); ++i) {
      const Vec<2> x = s2.points.col(i), n = s2.normals.col(i);
      CHECK(std::abs(m2.value(x)) <= 1e-9);
      CHECK(std::abs(m2.value(x + delta * n) - delta) <= 1e-9);
    }
    // Batch equals single-point evaluation.
    Eigen::VectorXd f;
    Points<3> G;
    m.evaluateBatch(s3.points, f, &G);
    for (int i = 0; i < s3.size(); ++i) {
      Vec<3> g;
      const double fx = m.evaluate(s3.points.col(i), &g);
      CHECK(std::abs(f(i) - fx) <= 1e-12 * (1 + g.norm()));
      CHECK((G.col(i) - g).norm() <= 1e-11 * (1 + g.norm()));
    }
  }
}
