// transform.method (auto / update / re-solve) and transform.matrix (the exact composition
// f(T⁻¹x) for maps outside the similarities).

#include <doctest/doctest.h>

#include <random>

#include "core/base/threading.h"
#include "scene/scene_fit.h"

using namespace hermite;

namespace {

Scene sphereScene() {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = 40;
  s.fit.kernel = KernelType::Cubic;
  s.fit.polynomial = Polynomial::Linear;
  s.transform.translate = {0.3, -0.2, 0.1};
  s.transform.rotateAxisAngleDeg = {1, 2, 3, 40};
  s.transform.scale = 1.7;
  return s;
}

}  // namespace

TEST_CASE("transform.method: auto uses the exact update, update / re-solve force one") {
  Scene s = sphereScene();
  const SceneFit<3> autoFit = fitScene<3>(s);
  CHECK(autoFit.transform.method == "coefficient-update");
  CHECK(autoFit.transform.exact);
  s.transform.method = TransformMethod::Resolve;
  const SceneFit<3> resolved = fitScene<3>(s);
  CHECK(resolved.transform.method == "re-solve");
  // Both are the interpolant of the transformed data here: the same field.
  const Vec<3> x(0.4, 0.9, -0.3);
  CHECK(autoFit.field().value(x) == doctest::Approx(resolved.field().value(x)).epsilon(1e-8));
  // With smoothing the update is not the re-solve: forcing it warns.
  s.fit.smoothing = 1e-3;
  s.transform.method = TransformMethod::Update;
  s.transform.verify = true;
  const SceneFit<3> forced = fitScene<3>(s);
  CHECK(forced.transform.method == "coefficient-update");
  CHECK_FALSE(forced.transform.exact);
  bool warned = false;
  for (const auto& w : forced.warnings) warned |= w.find("not the re-solved interpolant") != std::string::npos;
  CHECK(warned);
  REQUIRE(forced.transform.maxAbsDf);
  CHECK(*forced.transform.maxAbsDf > 0);
}

TEST_CASE("transform.verify: without it a transformed fit costs the update only and reports no comparison") {
  // One thread: a dense fit takes as many BLAS threads as there are idle cores, and one and two
  // threads round differently, so two fits of one scene are equal bit for bit only at a fixed
  // count (docs/cli.md, --threads).
  const int threads = threadCount();
  setThreadCount(1);
  Scene s = sphereScene();
  s.transform.translate = {0.5, -1, 2};
  s.transform.scale = 1.5;
  const SceneFit<3> plain = fitScene<3>(s);
  CHECK(plain.transform.method == "coefficient-update");
  CHECK_FALSE(plain.transform.resolveMs);
  CHECK_FALSE(plain.transform.maxAbsDf);
  CHECK_FALSE(plain.transform.maxGradDiff);
  s.transform.verify = true;
  const SceneFit<3> verified = fitScene<3>(s);
  REQUIRE(verified.transform.maxAbsDf);
  CHECK(*verified.transform.maxAbsDf <= 1e-9);  // the update is exact here
  CHECK(*verified.transform.resolveMs > 0);
  // Verification never changes the field that is used.
  const Vec<3> x(0.3, 0.2, -0.1);
  CHECK(plain.field().value(x) == verified.field().value(x));
  setThreadCount(threads);
}

TEST_CASE("transform.matrix: the composition f(T⁻¹x) with the gradient A⁻ᵀ∇f, and a real Lipschitz bound") {
  Scene s = sphereScene();
  s.transform.matrix = {2.0, 0.3, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5};  // non-uniform scale + shear
  const SceneFit<3> fit = fitScene<3>(s);
  CHECK(fit.transform.method == "composition");
  CHECK_FALSE(fit.transform.exact);
  REQUIRE(fit.composed);
  // The untransformed fit through the map by hand.
  Scene plain = s;
  plain.transform = TransformSpec{};
  plain.transform.translate = {0, 0, 0};
  const SceneFit<3> base = fitScene<3>(plain);
  Mat<3> M;
  M << 2.0, 0.3, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5;
  const Similarity<3> S = sceneSimilarity<3>(s.transform);
  const Mat<3> A = M * (S.q * S.R);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int k = 0; k < 50; ++k) {
    const Vec<3> x(u(rng), u(rng), u(rng));
    const Vec<3> y = A.inverse() * (x - S.t);
    Vec<3> gx, gy;
    const double fx = fit.field().evaluate(x, &gx), fy = base.field().evaluate(y, &gy);
    CHECK(fx == doctest::Approx(fy).epsilon(1e-12));
    CHECK((gx - A.inverse().transpose() * gy).norm() < 1e-9 * (1 + gy.norm()));
  }
  // The transformed samples are on the zero set; ‖∇g‖ ≤ L on a box.
  CHECK(fitResiduals(fit).maxAbsF < 1e-9);
  Box<3> box;
  box.lo = Vec<3>(-0.5, -0.5, -0.5);
  box.hi = Vec<3>(0.8, 0.6, 0.7);
  const double L = fit.field().lipschitzBound(box);
  for (int k = 0; k < 200; ++k) {
    const Vec<3> x = box.lo + (box.hi - box.lo).cwiseProduct(Vec<3>(u(rng) + 2, u(rng) + 2, u(rng) + 2) / 4);
    CHECK(fit.field().gradient(x).norm() <= L * (1 + 1e-12));
  }
}
