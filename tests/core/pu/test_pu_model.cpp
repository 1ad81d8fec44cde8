#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/base/errors.h"
#include "core/pu/pu_model.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

PuOptions options2d(int maxPoints, Kernel kernel = {KernelType::Gaussian, 0.2}, Polynomial poly = Polynomial::Linear) {
  PuOptions o;
  o.local = HrbfOptions{kernel, poly, 0.0};
  o.maxPointsPerBox = maxPoints;
  return o;
}

PuOptions options3d(Kernel kernel, int maxPoints = 20) {
  PuOptions o;
  o.local = HrbfOptions{kernel, Polynomial::Linear, 0.0};
  o.maxPointsPerBox = maxPoints;
  return o;
}

template <int Dim>
Vec<Dim> randomIn(std::mt19937& rng, const Box<Dim>& b) {
  std::uniform_real_distribution<double> u(0, 1);
  Vec<Dim> x;
  for (int k = 0; k < Dim; ++k) x(k) = b.lo(k) + u(rng) * (b.hi(k) - b.lo(k));
  return x;
}

}  // namespace

TEST_CASE("pu: the tree follows max_points_per_box and box_size, leaves tile the root") {
  const HermiteSamples<2> s = testing::ellipse(400);
  const PuTree<2> tree(s.points, {5, 0.0});
  int total = 0;
  double area = 0;
  for (int i = 0; i < tree.leafCount(); ++i) {
    CHECK(tree.leafSampleCount(i) <= 5);
    total += tree.leafSampleCount(i);
    area += tree.leafBox(i).extent().prod();
  }
  CHECK(total == 400);
  CHECK(area == doctest::Approx(tree.root().extent().prod()).epsilon(1e-12));
  const PuTree<2> sized(s.points, {1000, 0.3});
  for (int i = 0; i < sized.leafCount(); ++i)
    if (sized.leafSampleCount(i) > 0) CHECK(sized.leafBox(i).extent().maxCoeff() <= 0.3);
  // Every sample is located in the leaf that holds it.
  for (int i = 0; i < tree.leafCount(); ++i) {
    const auto& nd = tree.node(tree.leaves()[i]);
    for (int j = nd.begin; j < nd.end; ++j) CHECK(tree.locateLeaf(s.points.col(tree.order()[j])) == i);
  }
}

TEST_CASE("pu: the tree's k-th scaled distance from a box is the k-th of all samples' distances") {
  std::mt19937 rng(5);
  Points<3> P(3, 3000);
  for (int i = 0; i < P.cols(); ++i) P.col(i) = randomIn<3>(rng, Box<3>{Vec<3>::Zero(), Vec<3>(1, 0.5, 0.25)});
  const PuTree<3> tree(P, {20, 0.0});
  for (int q = 0; q < 50; ++q) {
    const Vec<3> c = randomIn<3>(rng, Box<3>{Vec<3>::Constant(-0.2), Vec<3>::Constant(1.2)});
    const Vec<3> h(0.01 + 0.1 * q / 50.0, 0.02, 0.05);
    const Box<3> box{c - h, c + h};
    std::vector<double> d;
    for (int i = 0; i < P.cols(); ++i)
      d.push_back(((P.col(i) - c).cwiseAbs().cwiseProduct(h.cwiseInverse())).maxCoeff());
    std::sort(d.begin(), d.end());
    for (int k : {1, 8, 16, 100})
      CHECK(tree.kthScaledDistance(box, k) == doctest::Approx(d[static_cast<std::size_t>(k - 1)]).epsilon(1e-14));
  }
  CHECK(tree.kthScaledDistance(tree.root(), 3001) == std::numeric_limits<double>::infinity());
}

TEST_CASE("pu: weights sum to one where there is data, and the fit interpolates") {
  const HermiteSamples<2> s = testing::ellipse(400);
  PuReport report;
  const PuModel<2> pu = fitPu<2>(s, options2d(5, {KernelType::Cubic, 1.0}), &report);
  CHECK(report.boxes == pu.tree().leafCount());
  CHECK(report.maxConditionEstimate < 1e12);
  CHECK(report.maxBoxSamples <= 5);
  std::mt19937 rng(7);
  for (int t = 0; t < 2000; ++t) {
    const Vec<2> x = randomIn<2>(rng, pu.tree().root());
    const auto w = pu.weights(x);
    // No weight: no data; where weights reach, the samples' reach may still say no data
    // (docs/maths.md, "No data").
    if (pu.valid(x)) CHECK_FALSE(w.empty());
    if (w.empty()) continue;
    double sum = 0;
    for (const auto& [leaf, wi] : w) {
      CHECK(wi > 0);
      sum += wi;
    }
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-14));
  }
  // Each support containing pᵢ holds pᵢ, so every local fit interpolates there: so does the blend.
  Eigen::VectorXd f;
  Points<2> G;
  pu.evaluateBatch(s.points, f, &G);
  CHECK(f.cwiseAbs().maxCoeff() < 1e-9);
  CHECK((G - s.normals).colwise().norm().maxCoeff() < 1e-7);
}

TEST_CASE("pu: f and grad f are continuous across box borders; derivatives match differences") {
  const HermiteSamples<2> s = testing::ellipse(200);
  for (const Kernel kernel : {Kernel{KernelType::Cubic, 1.0}, Kernel{KernelType::Wendland, 0.1}}) {
    PuReport report;
    const PuModel<2> pu = fitPu<2>(s, options2d(8, kernel, Polynomial::Linear), &report);
    CHECK(report.maxConditionEstimate < 1e12);
    const double eps = 1e-9;
    int faces = 0;
    for (int i = 0; i < pu.tree().leafCount(); ++i) {
      const Box<2>& b = pu.tree().leafBox(i);
      for (int k = 0; k < 2; ++k) {
        if (b.hi(k) >= pu.tree().root().hi(k)) continue;
        // Points on the upper face in axis k, sampled on both sides.
        for (double u : {0.13, 0.5, 0.87}) {
          Vec<2> x = b.center();
          x(k) = b.hi(k);
          x(1 - k) = b.lo(1 - k) + u * (b.hi(1 - k) - b.lo(1 - k));
          Vec<2> a = x, c = x;
          a(k) -= eps;
          c(k) += eps;
          Vec<2> ga, gc;
          const double fa = pu.evaluate(a, &ga), fc = pu.evaluate(c, &gc);
          const double scale = 1.0 + std::abs(fa) + ga.norm();
          CHECK(std::abs(fa - fc) <= 1e-7 * scale);  // a seam would jump by O(1)
          CHECK((ga - gc).norm() <= 1e-6 * scale);
          ++faces;
        }
      }
    }
    CHECK(faces > 20);
    // Gradient and Hessian against central differences.
    std::mt19937 rng(3);
    const double h = 1e-5;
    for (int t = 0; t < 200; ++t) {
      const Vec<2> x = randomIn<2>(rng, pu.tree().root());
      Vec<2> g;
      Mat<2> H;
      pu.evaluate(x, &g, &H);
      for (int k = 0; k < 2; ++k) {
        Vec<2> xp = x, xm = x;
        xp(k) += h;
        xm(k) -= h;
        Vec<2> gp, gm;
        const double fd = (pu.evaluate(xp, &gp) - pu.evaluate(xm, &gm)) / (2 * h);
        CHECK(fd == doctest::Approx(g(k)).epsilon(1e-5).scale(1.0 + g.norm()));
        const Vec<2> hd = (gp - gm) / (2 * h);
        CHECK((hd - H.col(k)).norm() <= 1e-4 * (1.0 + H.norm()));
      }
    }
  }
}

TEST_CASE("pu: one box covering everything equals the global fit where it has data") {
  const HermiteSamples<3> s = testing::goldenSphere(60);
  for (const Kernel kernel : {Kernel{KernelType::Cubic, 1.0}, Kernel{KernelType::Wendland, 2.0}}) {
    PuOptions o;
    o.local = HrbfOptions{kernel, Polynomial::Linear, 0.0};
    o.maxPointsPerBox = 1000;
    const PuModel<3> pu = fitPu<3>(s, o);
    REQUIRE(pu.tree().leafCount() == 1);
    const HrbfModel<3> global = fitHrbf<3>(s, o.local);
    std::mt19937 rng(11);
    Box<3> b{Vec<3>::Constant(-2), Vec<3>::Constant(2)};  // beyond the root box too
    for (int t = 0; t < 300; ++t) {
      const Vec<3> x = randomIn<3>(rng, b);
      Vec<3> g1, g2;
      const double f1 = pu.evaluate(x, &g1), f2 = global.evaluate(x, &g2);
      // Beyond the box's support there is no data (docs/maths.md, "No data").
      const Box<3>& support = pu.leaves()[0].support;
      const bool inSupport = ((x - support.center()).cwiseAbs().array() < 0.5 * support.extent().array()).all();
      CHECK(pu.valid(x) == inSupport);
      if (!inSupport) {
        CHECK(f1 == pu.noDataValue());
        continue;
      }
      CHECK(std::abs(f1 - f2) <= 1e-12 * (1 + std::abs(f2)));
      CHECK((g1 - g2).norm() <= 1e-12 * (1 + g2.norm()));
    }
  }
}

TEST_CASE("pu: empty and nearly empty boxes borrow neighbours; nothing is NaN anywhere") {
  // A dense cluster and two isolated samples: most boxes are empty or hold one sample.
  HermiteSamples<2> s = testing::ellipse(60, 0.2, 0.1);
  s.points.conservativeResize(2, 62);
  s.normals.conservativeResize(2, 62);
  s.points.col(60) = Vec<2>(3, 2);
  s.normals.col(60) = Vec<2>(0, 1);
  s.points.col(61) = Vec<2>(-2, 2.5);
  s.normals.col(61) = Vec<2>(1, 1).normalized();
  PuReport report;
  const PuModel<2> pu = fitPu<2>(s, options2d(3, {KernelType::Gaussian, 0.04}), &report);
  CHECK(report.grownSupports > 0);
  for (const auto& leaf : pu.leaves())
    if (leaf.blended) CHECK(leaf.samples >= 3);  // the others are not fitted (no data there)
  const Box<2> far{Vec<2>(-10, -10), Vec<2>(10, 10)};
  std::mt19937 rng(5);
  for (int t = 0; t < 3000; ++t) {
    Vec<2> g;
    Mat<2> H;
    const double f = pu.evaluate(randomIn<2>(rng, far), &g, &H);
    CHECK(std::isfinite(f));
    CHECK(g.allFinite());
    CHECK(H.allFinite());
  }
  Eigen::VectorXd f;
  pu.evaluateBatch(s.points, f);
  CHECK(f.cwiseAbs().maxCoeff() < 1e-8);
}

TEST_CASE("pu: duplicate and collinear samples inside a box") {
  // Collinear samples (a straight segment) with a quadratic term: a local system from them alone
  // is singular (the square of the line's equation vanishes with its gradient on all of them);
  // the support grows until the fit is regular.
  HermiteSamples<2> s = testing::ellipse(40);
  const int extra = 6;
  s.points.conservativeResize(2, 40 + extra);
  s.normals.conservativeResize(2, 40 + extra);
  for (int i = 0; i < extra; ++i) {
    s.points.col(40 + i) = Vec<2>(1.5 + 0.01 * i, 0.5);
    s.normals.col(40 + i) = Vec<2>(0, 1);
  }
  // One exact duplicate: merged by validation with a warning.
  s.points.conservativeResize(2, 47);
  s.normals.conservativeResize(2, 47);
  s.points.col(46) = s.points.col(41);
  s.normals.col(46) = s.normals.col(41);
  std::vector<std::string> warnings;
  validateSamples(s, warnings);
  REQUIRE(s.size() == 46);
  CHECK(!warnings.empty());
  PuReport report;
  const PuModel<2> pu = fitPu<2>(s, options2d(6, {KernelType::Cubic, 1.0}, Polynomial::Quadratic), &report);
  Eigen::VectorXd f;
  Points<2> G;
  pu.evaluateBatch(s.points, f, &G);
  CHECK(f.allFinite());
  CHECK(f.cwiseAbs().maxCoeff() < 1e-6);
  CHECK((G - s.normals).colwise().norm().maxCoeff() < 1e-5);
}

TEST_CASE("pu: the Lipschitz bound holds on boxes") {
  const HermiteSamples<3> s = testing::goldenSphere(300);
  const PuOptions o = options3d({KernelType::Gaussian, 0.5});
  const PuModel<3> pu = fitPu<3>(s, o);
  std::mt19937 rng(9);
  const Box<3> domain{Vec<3>::Constant(-1.6), Vec<3>::Constant(1.6)};
  int finite = 0;
  for (int t = 0; t < 40; ++t) {
    const Vec<3> a = randomIn<3>(rng, domain), c = randomIn<3>(rng, domain);
    Box<3> b{a.cwiseMin(c), a.cwiseMax(c)};
    b.hi = b.lo + 0.3 * (b.hi - b.lo);
    const double L = pu.lipschitzBound(b);
    // ∞ where the box reaches the edge of the data (f may jump to its no-data value there).
    if (!std::isfinite(L)) continue;
    ++finite;
    double gmax = 0;
    for (int k = 0; k < 200; ++k) gmax = std::max(gmax, pu.gradient(randomIn<3>(rng, b)).norm());
    CHECK(gmax <= L);
  }
  CHECK(finite >= 10);
  PuOptions hard = o;
  hard.blend = PuBlend::Hard;
  CHECK(std::isinf(fitPu<3>(s, hard).lipschitzBound(domain)));
}

TEST_CASE("pu: a transformed PU model keeps its tree and equals the re-solved one") {
  const HermiteSamples<3> s = testing::goldenSphere(200);
  Similarity<3> T;
  T.R = Eigen::AngleAxisd(0.9, Vec<3>(1, 2, -0.5).normalized()).toRotationMatrix();
  T.t = Vec<3>(0.4, -1.1, 2.0);
  T.q = 1.7;
  for (const Kernel kernel : {Kernel{KernelType::Gaussian, 0.5}, Kernel{KernelType::Cubic, 1.0}}) {
    PuOptions o;
    o.local = HrbfOptions{kernel, Polynomial::Linear, 0.0};
    o.maxPointsPerBox = 15;
    const PuModel<3> pu = fitPu<3>(s, o);
    const PuModel<3> moved = transformPu<3>(pu, T);
    const HermiteSamples<3> ms = transformSamples(s, T);
    const PuModel<3> resolved = fitPu<3>(ms, o, nullptr, T);
    // Same tree, moved through the frame.
    REQUIRE(moved.tree().leafCount() == pu.tree().leafCount());
    REQUIRE(resolved.tree().leafCount() == pu.tree().leafCount());
    CHECK((moved.frame().apply(pu.tree().root().lo) - T.apply(pu.tree().root().lo)).norm() < 1e-12);
    for (int i = 0; i < pu.tree().leafCount(); ++i) {
      CHECK((moved.leaves()[i].support.lo - resolved.leaves()[i].support.lo).norm() < 1e-12);
      CHECK(moved.leaves()[i].samples == resolved.leaves()[i].samples);
    }
    std::mt19937 rng(2);
    const Box<3> b{T.t - Vec<3>::Constant(2.5), T.t + Vec<3>::Constant(2.5)};
    double maxDf = 0, maxDg = 0, maxG = 0;
    for (int t = 0; t < 500; ++t) {
      const Vec<3> x = randomIn<3>(rng, b);
      Vec<3> g1, g2;
      const double f1 = moved.evaluate(x, &g1), f2 = resolved.evaluate(x, &g2);
      maxDf = std::max(maxDf, std::abs(f1 - f2));
      maxDg = std::max(maxDg, (g1 - g2).norm());
      maxG = std::max(maxG, g2.norm());
      // And q·f(T⁻¹x): the transform of the field itself.
      CHECK(f1 == doctest::Approx(T.q * pu.value(T.applyInverse(x))).epsilon(1e-9).scale(1.0));
    }
    CHECK(maxDf <= 1e-9 * (1 + maxG));
    CHECK(maxDg <= 1e-8 * (1 + maxG));
  }
}

TEST_CASE("pu: crowded supports split their box; dense samples of a sphere give |f|/|grad f| <= 1e-3 diagonal") {
  // A dense cluster beside big empty boxes: no support may hold more than the cap, except at the
  // depth limit.
  const HermiteSamples<3> s = testing::goldenSphere(4000);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.maxPointsPerBox = 20;
  o.maxSupportSamples = 60;
  PuReport report;
  const PuModel<3> pu = fitPu<3>(s, o, &report);
  CHECK(report.maxSupportSamples <= 60);
  // Held-out exact points of the sphere (a different spiral): first-order distance to the zero set.
  const HermiteSamples<3> fresh = testing::goldenSphere(997);
  Eigen::VectorXd f;
  Points<3> G;
  pu.evaluateBatch(fresh.points, f, &G);
  const double diagonal = std::sqrt(12.0);
  double worst = 0;
  for (int i = 0; i < fresh.size(); ++i) worst = std::max(worst, std::abs(f(i)) / G.col(i).norm());
  CHECK(worst <= 1e-3 * diagonal);
  // The Lipschitz bound also holds for a transformed (rotated, scaled) model.
  Similarity<3> T;
  T.R = Eigen::AngleAxisd(0.6, Vec<3>(0.2, 1, 0.3).normalized()).toRotationMatrix();
  T.q = 0.7;
  T.t = Vec<3>(1, 0, -1);
  const PuModel<3> moved = transformPu<3>(pu, T);
  std::mt19937 rng(13);
  for (int t = 0; t < 20; ++t) {
    const Vec<3> c = T.apply(randomIn<3>(rng, Box<3>{Vec<3>::Constant(-1.2), Vec<3>::Constant(1.2)}));
    const Box<3> b{c - Vec<3>::Constant(0.1), c + Vec<3>::Constant(0.1)};
    const double L = moved.lipschitzBound(b);
    double gmax = 0;
    for (int k = 0; k < 100; ++k) gmax = std::max(gmax, moved.gradient(randomIn<3>(rng, b)).norm());
    CHECK(gmax <= L);
  }
}

// Points in rows along the first axis across `box` (runs that share a walk of the tree), then the
// same points shuffled (runs of scattered points, evaluated point by point): each point gets the
// same f and ∇f bit for bit, within 1e-12 of the single-point evaluation; some have data, some not.
template <int Dim>
void checkBatchOrder(const PuModel<Dim>& pu, const Box<Dim>& box) {
  const int rows = 50, perRow = 64;
  std::mt19937 rng(5);
  Points<Dim> X(Dim, rows * perRow);
  for (int r = 0; r < rows; ++r) {
    Vec<Dim> start = randomIn<Dim>(rng, box);
    for (int k = 0; k < perRow; ++k) {
      X.col(r * perRow + k) = start;
      X(0, r * perRow + k) = box.lo(0) + (box.hi(0) - box.lo(0)) * k / (perRow - 1);
    }
  }
  std::vector<Eigen::Index> order(static_cast<std::size_t>(X.cols()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<Eigen::Index>(i);
  std::shuffle(order.begin(), order.end(), rng);
  const Points<Dim> Y = X(Eigen::all, order);
  Eigen::VectorXd fx, fy;
  Points<Dim> gx, gy;
  pu.evaluateBatch(X, fx, &gx);
  pu.evaluateBatch(Y, fy, &gy);
  int differ = 0, far = 0;
  double worst = 0;
  for (Eigen::Index k = 0; k < Y.cols(); ++k) {
    const Eigen::Index i = order[static_cast<std::size_t>(k)];
    differ += fy(k) != fx(i) || gy.col(k) != gx.col(i);
    const double f = pu.evaluate(X.col(i));
    worst = std::max(worst, std::abs(f - fx(i)) / (1 + std::abs(f)));
    far += fx(i) == pu.noDataValue();
  }
  CHECK(differ == 0);
  CHECK(worst < 1e-12);
  CHECK(far > 0);
  CHECK(far < X.cols());
}

TEST_CASE("pu: batch evaluation gives each point the same value in any order, scattered or in rows") {
  const PuModel<3> sphere = fitPu<3>(testing::goldenSphere(3000), options3d({KernelType::Cubic, 1.0}));
  checkBatchOrder<3>(sphere, Box<3>{Vec<3>::Constant(-1.2), Vec<3>::Constant(1.2)});
  const PuModel<2> ellipse = fitPu<2>(testing::ellipse(2000), options2d(10, {KernelType::Cubic, 1.0}));
  checkBatchOrder<2>(ellipse, Box<2>{Vec<2>(-1.3, -0.8), Vec<2>(1.3, 0.8)});
}
