#include <doctest/doctest.h>

#include <random>

#include "core/base/errors.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/analytic_shapes.h"
#include "core/trace/default_view_bounds.h"
#include "core/trace/volume_bake.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// A random Gaussian HRBF-like sum with a linear polynomial: many small bubbles and saddles.
RadialSum<3> randomField(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1, 1);
  Points<3> c(3, n), beta(3, n);
  Eigen::VectorXd alpha(n), poly(4);
  for (int j = 0; j < n; ++j) {
    c.col(j) = Vec<3>(u(rng), u(rng), u(rng));
    beta.col(j) = 0.3 * Vec<3>(u(rng), u(rng), u(rng));
    alpha(j) = u(rng);
  }
  poly << 0.1 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng);
  return RadialSum<3>(Kernel{KernelType::Gaussian, 0.35}, Polynomial::Linear, c, alpha, beta, poly);
}

Box<3> cube(double h) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-h);
  b.hi = Vec<3>::Constant(h);
  return b;
}

}  // namespace

TEST_CASE("volume bake: values equal direct evaluation, x fastest") {
  const HrbfModel<3> model = fitHrbf<3>(testing::blob(40), {});
  Box<3> bounds = defaultViewBounds<3>(testing::blob(40).points);
  bounds.hi.z() += 0.3;  // not a cube: axes distinguishable
  const VolumeBake bake = bakeVolume(model, bounds, {17, 4});
  REQUIRE(bake.values.size() == 17u * 17u * 17u);
  CHECK((bake.samplePosition(16, 16, 16) - bounds.hi).norm() < 1e-12);
  CHECK((bake.samplePosition(0, 0, 0) - bounds.lo).norm() == 0.0);
  double maxErr = 0;
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i) {
        const double f = model.value(bake.samplePosition(i, j, k));
        maxErr = std::max(maxErr, std::abs(double(bake.values[i + 17 * (j + 17 * k)]) - f) / (1 + std::abs(f)));
      }
  CHECK(maxErr < 1e-6);  // float storage
  CHECK(bake.bricks.count.x() == 4);
  CHECK((bake.bricks.brickBox(3, 3, 3).hi - bounds.hi).norm() == 0.0);
  CHECK(bake.bricks.brickBox(1, 0, 0).lo.x() == doctest::Approx(bake.samplePosition(4, 0, 0).x()));
  CHECK_THROWS_AS(bakeVolume(model, bounds, {1, 4}), InputError);
}

TEST_CASE("volume bake: partial last brick covers the remaining cells") {
  const SphereField sphere(Vec<3>::Zero(), 0.7);
  const VolumeBake bake = bakeVolume(sphere, cube(1.0), {12, 4});  // 11 cells: bricks of 4, 4, 3
  REQUIRE(bake.bricks.count.x() == 3);
  CHECK(bake.bricks.brickBox(2, 0, 0).hi.x() == 1.0);
  CHECK(bake.bricks.brickBox(2, 0, 0).lo.x() == doctest::Approx(bake.samplePosition(8, 0, 0).x()));
  for (int b = 0; b < bake.bricks.brickCount(); ++b) CHECK(bake.brickMin[b] <= bake.brickMax[b]);
}

TEST_CASE("volume bake: brick Lipschitz bounds dominate |∇f| at random points in the brick") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const HrbfModel<3> hrbf = fitHrbf<3>(testing::blob(50), {});
  const RadialSum<3> random = randomField(rng, 30);
  for (const ImplicitField<3>* field : {static_cast<const ImplicitField<3>*>(&hrbf),
                                        static_cast<const ImplicitField<3>*>(&random)}) {
    const BrickGrid grid = computeBrickGrid(*field, cube(1.3), Eigen::Array3i(6, 5, 4));
    for (int trial = 0; trial < 2000; ++trial) {
      const int bx = int(u(rng) * 6), by = int(u(rng) * 5), bz = int(u(rng) * 4);
      const Box<3> box = grid.brickBox(bx, by, bz);
      const Vec<3> x = box.lo + box.extent().cwiseProduct(Vec<3>(u(rng), u(rng), u(rng)));
      CHECK(field->gradient(x).norm() <= grid.lipschitz[grid.index(bx, by, bz)] * (1 + 1e-12));
    }
  }
}

TEST_CASE("volume bake: the no-crossing test never culls a brick that contains a zero") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int culled = 0, kept = 0;
  for (int fieldIndex = 0; fieldIndex < 6; ++fieldIndex) {
    const RadialSum<3> field = randomField(rng, 12);
    const VolumeBake bake = bakeVolume(field, cube(1.2), {25, 3});
    const BrickGrid& g = bake.bricks;
    for (int bz = 0; bz < g.count.z(); ++bz)
      for (int by = 0; by < g.count.y(); ++by)
        for (int bx = 0; bx < g.count.x(); ++bx) {
          const int b = g.index(bx, by, bz);
          // Baked samples straddling 0 are a zero the test must not cull.
          if (bake.brickMin[b] < 0 && bake.brickMax[b] > 0) CHECK(g.mayContainZero[b] == 1);
          if (g.mayContainZero[b]) {
            ++kept;
            continue;
          }
          ++culled;
          const Box<3> box = g.brickBox(bx, by, bz);
          const double s = g.centerValue[b] > 0 ? 1.0 : -1.0;
          for (int trial = 0; trial < 40; ++trial) {
            const Vec<3> x = box.lo + box.extent().cwiseProduct(Vec<3>(u(rng), u(rng), u(rng)));
            CHECK(s * field.value(x) > 0);
          }
        }
  }
  CHECK(culled > 0);  // the test has teeth
  CHECK(kept > 0);
}

TEST_CASE("volume bake: the row-wise cubic path equals direct evaluation (HRBF and plain RBF, full and partial rows)") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 37;
  Points<3> c(3, n), beta(3, n);
  Eigen::VectorXd alpha(n), quad(10);
  for (int j = 0; j < n; ++j) {
    c.col(j) = Vec<3>(u(rng), u(rng), u(rng));
    beta.col(j) = 0.3 * Vec<3>(u(rng), u(rng), u(rng));
    alpha(j) = u(rng);
  }
  for (int k = 0; k < 10; ++k) quad(k) = 0.2 * u(rng);
  // A centre exactly on a grid sample (x = 0 there: the limits must hold).
  c.col(0) = Vec<3>::Zero();
  const RadialSum<3> hrbf(Kernel{KernelType::Cubic, 1.0}, Polynomial::Linear, c, alpha, beta, quad.head(4));
  const RadialSum<3> plain(Kernel{KernelType::Cubic, 1.0}, Polynomial::Quadratic, c, alpha, Points<3>(3, 0), quad);
  for (const RadialSum<3>* field : {&hrbf, &plain})
    for (int R : {65, 70}) {  // 65: whole vectors and a partial one; 70: a partial chunk
      CAPTURE(R);
      const VolumeBake bake = bakeVolume(*field, cube(1.0), {R, 8});
      double maxErr = 0;
      for (int k = 0; k < R; k += 3)
        for (int j = 0; j < R; j += 2)
          for (int i = 0; i < R; ++i) {
            const double f = field->value(bake.samplePosition(i, j, k));
            maxErr = std::max(maxErr, std::abs(double(bake.value(i, j, k)) - f) / (1 + std::abs(f)));
          }
      CHECK(maxErr < 1e-6);  // float storage
    }
}

namespace {

// f = 0.3 + x − 2y + 0.5z + 1.5xyz: trilinear, so the bake's interpolant reproduces it exactly
// (up to float storage) inside the bounds.
class TrilinearField final : public ImplicitField<3> {
 public:
  double evaluate(const Vec<3>& p, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const double x = p.x(), y = p.y(), z = p.z();
    if (g) *g = Vec<3>(1 + 1.5 * y * z, -2 + 1.5 * x * z, 0.5 + 1.5 * x * y);
    if (H) *H << 0, 1.5 * z, 1.5 * y, 1.5 * z, 0, 1.5 * x, 1.5 * y, 1.5 * x, 0;
    return 0.3 + x - 2 * y + 0.5 * z + 1.5 * x * y * z;
  }
  double lipschitzBound(const Box<3>&) const override { return 10.0; }
};

}  // namespace

TEST_CASE("volume bake: the interpolant reproduces a trilinear field and clamps outside the bounds") {
  const TrilinearField field;
  Box<3> bounds = cube(1.0);
  bounds.hi.y() = 0.5;
  const VolumeBake bake = bakeVolume(field, bounds, {9, 4});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  double maxErr = 0;
  for (int k = 0; k < 500; ++k) {
    const Vec<3> x = bounds.lo + bounds.extent().cwiseProduct(Vec<3>(u(rng), u(rng), u(rng)));
    maxErr = std::max(maxErr, std::abs(bake.interpolate(x) - field.value(x)));
  }
  CHECK(maxErr < 1e-5);
  const Vec<3> outside(1.7, -3.0, 0.2), projected(1.0, -1.0, 0.2);
  CHECK(bake.interpolate(outside) == bake.interpolate(projected));
  CHECK(bake.interpolate(bounds.hi) == doctest::Approx(field.value(bounds.hi)).epsilon(1e-6));
}
