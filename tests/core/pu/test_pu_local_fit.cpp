#include <doctest/doctest.h>

#include <random>

#include "core/pu/pu_local_fit.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// A patch of a local fit's size: the first n samples of a golden-spiral blob (a wavy sphere),
// shifted off the origin as a box far from the frame's centre would be.
HermiteSamples<3> localPatch(int n, const Vec<3>& shift) {
  HermiteSamples<3> all = testing::blob(4 * n);
  HermiteSamples<3> s;
  s.points = all.points.leftCols(n).colwise() + shift;
  s.normals = all.normals.leftCols(n);
  return s;
}

// Largest |f_a − f_b| over random points of the patch's box grown by 50 %, relative to the box diagonal.
double fieldDifference(const HrbfModel<3>& a, const HrbfModel<3>& b, const HermiteSamples<3>& s) {
  const Vec<3> lo = s.points.rowwise().minCoeff(), hi = s.points.rowwise().maxCoeff();
  const Vec<3> c = 0.5 * (lo + hi), h = 0.75 * (hi - lo);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec<3> x = c + Vec<3>(u(rng), u(rng), u(rng)).cwiseProduct(h);
    worst = std::max(worst, std::abs(a.value(x) - b.value(x)));
  }
  return worst / (hi - lo).norm();
}

}  // namespace

TEST_CASE("pu local fit: cubic + linear takes nullspace-cholesky and matches the saddle's LU") {
  for (int n : {6, 20, 60}) {
    CAPTURE(n);
    const HermiteSamples<3> s = localPatch(n, Vec<3>(3.0, -2.0, 5.0));
    HrbfOptions o{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
    FitReport fast;
    const HrbfModel<3> a = fitPuLocal<3>(s, o, fast);
    CHECK(fast.solver == "nullspace-cholesky");
    CHECK(fast.nUnknowns == 4 * n + 4);
    o.solver = SolverChoice::Lu;  // an explicit solver: the LAPACK path of fitHrbf
    FitReport lu;
    const HrbfModel<3> b = fitPuLocal<3>(s, o, lu);
    CHECK(lu.solver == "lu");
    CHECK(fieldDifference(a, b, s) < 1e-9);
    // Interpolation: f(pᵢ) = 0 and ∇f(pᵢ) = nᵢ.
    for (int i = 0; i < n; ++i) {
      Vec<3> g;
      CHECK(std::abs(a.evaluate(s.points.col(i), &g)) < 1e-9);
      CHECK((g - s.normals.col(i)).norm() < 1e-7);
    }
  }
}

TEST_CASE("pu local fit: a positive definite kernel without polynomial takes cholesky, with one nullspace-cholesky") {
  const HermiteSamples<3> s = localPatch(30, Vec<3>::Zero());
  FitReport plain, linear;
  const HrbfModel<3> a = fitPuLocal<3>(s, {{KernelType::Gaussian, 1.0}, Polynomial::None, 0.0}, plain);
  CHECK(plain.solver == "cholesky");
  const HrbfModel<3> b = fitPuLocal<3>(s, {{KernelType::Gaussian, 1.0}, Polynomial::Linear, 0.0}, linear);
  CHECK(linear.solver == "nullspace-cholesky");
  for (int i = 0; i < s.size(); ++i) {
    CHECK(std::abs(a.value(s.points.col(i))) < 1e-8);
    CHECK(std::abs(b.value(s.points.col(i))) < 1e-8);
  }
}

TEST_CASE("pu local fit: a kernel of no known definiteness falls through to LU") {
  // Multiquadric without the polynomial its conditional definiteness needs: sign 0.
  const HermiteSamples<3> s = localPatch(20, Vec<3>::Zero());
  HrbfOptions o{{KernelType::Multiquadric, 0.5}, Polynomial::None, 0.0};
  REQUIRE(kernelDefiniteSign(o.kernel, o.polynomial, o.smoothing) == 0);
  FitReport r;
  const HrbfModel<3> a = fitPuLocal<3>(s, o, r);
  CHECK(r.solver == "lu");
  for (int i = 0; i < s.size(); ++i) CHECK(std::abs(a.value(s.points.col(i))) < 1e-7);
}
