// Every kernel of the table through each CPU path: the scalar evaluate, the batch loops
// (vectorised, AVX-512 where built) and the grid bake, against a direct sum of the reference
// kernel terms (Kernel::terms). The GLSL path has its own test in tests/render.

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/rbf/kernels.h"
#include "core/rbf/radial_sum.h"
#include "core/trace/volume_bake.h"

using namespace hermite;

namespace {

// f(x) = Σⱼ αⱼ φ(‖x − cⱼ‖) − βⱼ·∇φ(x − cⱼ) with ∇φ(d) = a(‖d‖)·d, and the same sum of
// absolute terms (the size rounding scales with).
template <int Dim>
std::pair<double, double> referenceSum(const RadialSum<Dim>& s, const Vec<Dim>& x) {
  double f = 0, size = 0;
  for (Eigen::Index j = 0; j < s.centres().cols(); ++j) {
    const Vec<Dim> d = x - s.centres().col(j);
    const RadialTerms t = s.kernel().terms(d.norm());
    const double value = s.alpha()(j) * t.phi;
    const double dipole = s.hasBeta() ? -t.a * s.beta().col(j).dot(d) : 0.0;
    f += value + dipole;
    size += std::abs(value) + std::abs(dipole);
  }
  return {f, size};
}

template <int Dim>
RadialSum<Dim> randomSum(const Kernel& kernel, bool beta, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 37;  // not a multiple of 8: the padded tail of the batch loops runs too
  Points<Dim> c(Dim, n), b(Dim, beta ? n : 0);
  Eigen::VectorXd a(n);
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < Dim; ++k) c(k, j) = u(rng);
    a(j) = u(rng);
    if (beta)
      for (int k = 0; k < Dim; ++k) b(k, j) = u(rng);
  }
  return RadialSum<Dim>(kernel, Polynomial::None, c, a, b, Eigen::VectorXd());
}

template <int Dim>
void checkBackends(const Kernel& kernel, bool beta, std::mt19937& rng) {
  const RadialSum<Dim> s = randomSum<Dim>(kernel, beta, rng);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  Points<Dim> X(Dim, 53);
  for (Eigen::Index i = 0; i < X.cols(); ++i)
    for (int k = 0; k < Dim; ++k) X(k, i) = u(rng);
  X.col(0) = s.centres().col(3);  // on a centre
  Eigen::VectorXd batch;
  s.evaluateBatch(X, batch);
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    const auto [f, size] = referenceSum<Dim>(s, X.col(i));
    const double tolerance = 1e-13 * std::max(size, 1e-300) + 1e-300;
    CHECK(std::abs(s.evaluate(X.col(i)) - f) <= tolerance);
    CHECK(std::abs(batch(i) - f) <= tolerance);
  }
}

}  // namespace

TEST_CASE("every kernel of the table: scalar and batch evaluation equal the reference terms, 2D and 3D") {
  std::mt19937 rng(7);
  for (const KernelInfo& info : kKernelTable) {
    for (bool beta : {false, true}) {
      CAPTURE(info.name);
      CAPTURE(beta);
      const Kernel kernel{info.type, 0.8};
      checkBackends<2>(kernel, beta, rng);
      checkBackends<3>(kernel, beta, rng);
    }
  }
}

TEST_CASE("every kernel of the table: the grid bake equals the reference terms at the grid nodes") {
  std::mt19937 rng(11);
  for (const KernelInfo& info : kKernelTable) {
    CAPTURE(info.name);
    const RadialSum<3> s = randomSum<3>(Kernel{info.type, 0.8}, true, rng);
    const Box<3> bounds{Vec<3>::Constant(-1), Vec<3>::Constant(1)};
    const int R = 9;
    VolumeBakeOptions options;
    options.resolution = R;
    options.brickCells = 4;
    const VolumeBake bake = bakeVolume(s, bounds, options);
    for (int z = 0; z < R; z += 4)
      for (int y = 0; y < R; y += 4)
        for (int x = 0; x < R; ++x) {
          const Vec<3> p = bake.samplePosition(x, y, z);
          const auto [f, size] = referenceSum<3>(s, p);
          // The bake stores floats: half a float ulp of the terms' size, plus its rounding.
          CHECK(std::abs(double(bake.value(x, y, z)) - f) <= 1e-6 * std::max(size, 1e-30));
        }
  }
}

TEST_CASE("batch evaluation inside a parallel region (the PU blend's runs) equals the threaded one bit for bit") {
  // Inside a parallel region the batch loop runs on the calling thread instead of entering a
  // nested region; each f(i) and ∇f(i) must not depend on which path or thread computed it.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  for (const KernelInfo& info : kKernelTable) {
    CAPTURE(info.name);
    const RadialSum<3> s = randomSum<3>(Kernel{info.type, 0.8}, true, rng);
    Points<3> X(3, 101);  // more than one chunk of 16 points
    for (Eigen::Index i = 0; i < X.cols(); ++i)
      for (int k = 0; k < 3; ++k) X(k, i) = u(rng);
    Eigen::VectorXd f;
    Points<3> G;
    s.evaluateBatch(X, f, &G);
    int mismatches = 0;
#pragma omp parallel reduction(+ : mismatches)
    {
      Eigen::VectorXd fi;
      Points<3> Gi;
      s.evaluateBatch(X, fi, &Gi);
      mismatches += (fi.array() != f.array()).count() + (Gi.array() != G.array()).count();
    }
    CHECK(mismatches == 0);
  }
}
