#include <doctest/doctest.h>

#include <algorithm>
#include <random>

#include "core/base/errors.h"
#include "core/rbf/hrbf.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

struct Config {
  Kernel kernel;
  Polynomial polynomial;
};

// Every kernel with every polynomial option that makes the fit well posed (degree ≥ order − 1).
std::vector<Config> wellPosedConfigs() {
  std::vector<Config> out;
  const std::vector<Kernel> kernels{{KernelType::Gaussian, 0.6},          {KernelType::Wendland, 1.8},
                                    {KernelType::Multiquadric, 0.8},      {KernelType::InverseMultiquadric, 0.8},
                                    {KernelType::Cubic, 1.0},             {KernelType::Polyharmonic, 1.0}};
  for (const Kernel& k : kernels)
    for (Polynomial p : {Polynomial::None, Polynomial::Linear, Polynomial::Quadratic})
      if (polynomialDegree(p) >= k.cpdOrder() - 1) out.push_back({k, p});
  return out;
}

template <int Dim>
void checkInterpolation(const HermiteSamples<Dim>& s, const Config& c) {
  CAPTURE(kernelName(c.kernel.type));
  CAPTURE(polynomialName(c.polynomial));
  FitReport rep;
  const HrbfModel<Dim> model = fitHrbf<Dim>(s, {c.kernel, c.polynomial, 0.0, SolverChoice::Auto}, &rep);
  CAPTURE(rep.solver);
  CAPTURE(rep.conditionEstimate);
  CHECK(rep.nUnknowns == s.size() * (Dim + 1) + monomialCount<Dim>(c.polynomial));
  Eigen::VectorXd f;
  Points<Dim> G;
  model.evaluateBatch(s.points, f, &G);
  // Data scale is 1 (unit normals, points in the unit ball): residuals relative to it.
  CHECK(f.cwiseAbs().maxCoeff() <= 1e-9);
  CHECK((G - s.normals).cwiseAbs().maxCoeff() <= 1e-8);
}

}  // namespace

TEST_CASE("HRBF interpolates points and normals in 2D for every kernel and well-posed polynomial") {
  const HermiteSamples<2> s = testing::ellipse(24);
  for (const Config& c : wellPosedConfigs()) checkInterpolation<2>(s, c);
}

TEST_CASE("HRBF interpolates points and normals in 3D for every kernel and well-posed polynomial") {
  const HermiteSamples<3> s = testing::blob(40);
  for (const Config& c : wellPosedConfigs()) checkInterpolation<3>(s, c);
}

TEST_CASE("quadratic + polyharmonic reproduces a sphere exactly") {
  // f = (‖x‖² − 1)/2 has f = 0 and ∇f = x = n on the unit sphere and lies in the polynomial space:
  // the unique interpolant is that quadratic, with α = β = 0.
  const HermiteSamples<3> s = testing::goldenSphere(30);
  const HrbfModel<3> m = fitHrbf<3>(s, {{KernelType::Polyharmonic, 1.0}, Polynomial::Quadratic, 0.0});
  CHECK(m.alpha().cwiseAbs().maxCoeff() <= 1e-9);
  CHECK(m.beta().cwiseAbs().maxCoeff() <= 1e-9);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 50; ++i) {
    const Vec<3> x(u(rng), u(rng), u(rng));
    Vec<3> g;
    const double f = m.evaluate(x, &g);
    CHECK(std::abs(f - 0.5 * (x.squaredNorm() - 1.0)) <= 1e-9);
    CHECK((g - x).norm() <= 1e-9);
  }
}

TEST_CASE("Cholesky, null-space Cholesky, LDLT and LU give the same coefficients") {
  const HermiteSamples<3> s = testing::blob(30);
  struct Case {
    Kernel kernel;
    Polynomial poly;
    std::vector<SolverChoice> solvers;
  };
  const std::vector<Case> cases{
      {{KernelType::Gaussian, 0.6}, Polynomial::None, {SolverChoice::Cholesky, SolverChoice::Ldlt, SolverChoice::Lu}},
      {{KernelType::Cubic, 1}, Polynomial::Linear,
       {SolverChoice::NullspaceCholesky, SolverChoice::Ldlt, SolverChoice::Lu}},
      {{KernelType::Multiquadric, 0.8}, Polynomial::Linear,
       {SolverChoice::NullspaceCholesky, SolverChoice::Ldlt, SolverChoice::Lu}},
      {{KernelType::Polyharmonic, 1}, Polynomial::Quadratic,
       {SolverChoice::NullspaceCholesky, SolverChoice::Ldlt, SolverChoice::Lu}},
  };
  for (const Case& c : cases) {
    CAPTURE(kernelName(c.kernel.type));
    std::vector<HrbfModel<3>> models;
    for (SolverChoice sc : c.solvers) {
      FitReport rep;
      models.push_back(fitHrbf<3>(s, {c.kernel, c.poly, 0.0, sc}, &rep));
      CHECK(rep.solver == std::string(solverName(sc)));
      CHECK(rep.warnings.empty());
    }
    const double scale = models[0].alpha().cwiseAbs().maxCoeff() + models[0].beta().cwiseAbs().maxCoeff();
    for (size_t i = 1; i < models.size(); ++i) {
      CHECK((models[i].alpha() - models[0].alpha()).cwiseAbs().maxCoeff() <= 1e-9 * scale);
      CHECK((models[i].beta() - models[0].beta()).cwiseAbs().maxCoeff() <= 1e-9 * scale);
      CHECK((models[i].poly() - models[0].poly()).norm() <= 1e-9 * (1 + models[0].poly().norm()));
    }
  }
}

TEST_CASE("smoothing with the §3 sign keeps the definite solver working where the wrong sign does not") {
  // Multiquadric is conditionally negative definite: Zᵀ A Z < 0. λ enters as −λ; +λ larger than
  // the smallest |eigenvalue| makes the projected matrix indefinite (towards singular on the way).
  const HermiteSamples<3> s = testing::blob(30);
  HrbfOptions o{{KernelType::Multiquadric, 0.8}, Polynomial::Linear, 0.5, SolverChoice::NullspaceCholesky};
  FitReport rep;
  fitHrbf<3>(s, o, &rep);
  CHECK(rep.solver == "nullspace-cholesky");
  CHECK(rep.warnings.empty());

  SaddleSystem wrong = assembleHrbf<3>(s, o);
  wrong.A.diagonal().array() += 2.0 * o.smoothing;  // −λ → +λ
  const SaddleSolution sol = solveSaddle(wrong, SolverChoice::NullspaceCholesky);
  CHECK(sol.solver == "lu");
  REQUIRE_FALSE(sol.warnings.empty());
  CHECK(sol.warnings[0].find("not positive definite") != std::string::npos);
}

TEST_CASE("smoothing approximates: residuals grow with λ and stay finite") {
  const HermiteSamples<3> s = testing::blob(30);
  double previous = 0.0;
  for (double lambda : {1e-6, 1e-3, 1e-1}) {
    const HrbfModel<3> m = fitHrbf<3>(s, {{KernelType::Cubic, 1}, Polynomial::Linear, lambda});
    Eigen::VectorXd f;
    m.evaluateBatch(s.points, f);
    const double res = f.cwiseAbs().maxCoeff();
    CHECK(std::isfinite(res));
    CHECK(res > previous);
    previous = res;
  }
}

TEST_CASE("polynomial below the kernel's order gives a warning") {
  const HermiteSamples<3> s = testing::blob(20);
  FitReport rep;
  fitHrbf<3>(s, {{KernelType::Cubic, 1}, Polynomial::None, 0.0}, &rep);
  REQUIRE_FALSE(rep.warnings.empty());
  CHECK(rep.warnings[0].find("below the order") != std::string::npos);
}

TEST_CASE("a polynomial term the samples cannot determine is a numerical error with its reason") {
  // Two samples on a line cannot determine a quadratic.
  HermiteSamples<3> s;
  s.points = Points<3>::Zero(3, 2);
  s.points(0, 1) = 1.0;
  s.normals = Points<3>::Zero(3, 2);
  s.normals(2, 0) = s.normals(2, 1) = 1.0;
  CHECK_THROWS_WITH_AS(fitHrbf<3>(s, {{KernelType::Gaussian, 1}, Polynomial::Quadratic, 0.0}),
                       doctest::Contains("polynomial term"), NumericalError);
  // Enough conditions (4 samples: 16 ≥ 10) but all on the x axis: y², z², yz are never seen.
  HermiteSamples<3> line;
  line.points = Points<3>::Zero(3, 4);
  line.normals = Points<3>::Zero(3, 4);
  for (int i = 0; i < 4; ++i) {
    line.points(0, i) = i;
    line.normals(2, i) = 1.0;
  }
  CHECK_THROWS_WITH_AS(fitHrbf<3>(line, {{KernelType::Gaussian, 1}, Polynomial::Quadratic, 0.0}),
                       doctest::Contains("dependent"), NumericalError);
}

TEST_CASE("model gradient and Hessian match finite differences, batch matches single-point evaluation") {
  const HermiteSamples<3> s3 = testing::blob(25);
  const HermiteSamples<2> s2 = testing::ellipse(16);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  for (const Config& c : wellPosedConfigs()) {
    CAPTURE(kernelName(c.kernel.type));
    CAPTURE(polynomialName(c.polynomial));
    const HrbfModel<3> m = fitHrbf<3>(s3, {c.kernel, c.polynomial, 0.0});
    Points<3> X(3, 20);
    for (int i = 0; i < 20; ++i) X.col(i) = Vec<3>(u(rng), u(rng), u(rng));
    X.col(0) = s3.points.col(3) + Vec<3>(1e-4, -2e-4, 1e-4);  // next to a centre
    X.col(1) = s3.points.col(5);                              // on a centre
    Eigen::VectorXd f;
    Points<3> G;
    m.evaluateBatch(X, f, &G);
    Eigen::VectorXd fOnly;
    m.evaluateBatch(X, fOnly);
    for (int i = 0; i < 20; ++i) {
      const Vec<3> x = X.col(i);
      Vec<3> g;
      Mat<3> H;
      const double fx = m.evaluate(x, &g, &H);
      const double scale = 1.0 + std::abs(fx) + g.norm();
      CHECK(std::abs(f(i) - fx) <= 1e-11 * scale);
      CHECK(std::abs(fOnly(i) - fx) <= 1e-11 * scale);
      CHECK((G.col(i) - g).norm() <= 1e-11 * scale);
      const double h = 1e-6;
      for (int k = 0; k < 3; ++k) {
        Vec<3> xp = x, xm = x;
        xp(k) += h;
        xm(k) -= h;
        Vec<3> gp, gm;
        const double fp = m.evaluate(xp, &gp), fm = m.evaluate(xm, &gm);
        CHECK(std::abs((fp - fm) / (2 * h) - g(k)) <= 1e-6 * scale);
        if (i != 1)  // the cubic/polyharmonic Hessian has no limit on a centre
          CHECK(((gp - gm) / (2 * h) - H.col(k)).norm() <= 1e-5 * (1 + H.norm()));
      }
    }
    const HrbfModel<2> m2 = fitHrbf<2>(s2, {c.kernel, c.polynomial, 0.0});
    Points<2> X2(2, 10);
    for (int i = 0; i < 10; ++i) X2.col(i) = Vec<2>(u(rng), u(rng));
    Eigen::VectorXd f2;
    Points<2> G2;
    m2.evaluateBatch(X2, f2, &G2);
    for (int i = 0; i < 10; ++i) {
      Vec<2> g;
      const double fx = m2.evaluate(X2.col(i), &g);
      CHECK(std::abs(f2(i) - fx) <= 1e-11 * (1 + std::abs(fx) + g.norm()));
      CHECK((G2.col(i) - g).norm() <= 1e-11 * (1 + std::abs(fx) + g.norm()));
    }
  }
}

TEST_CASE("Lipschitz bound of a fitted model dominates the gradient over a box") {
  const HermiteSamples<3> s = testing::blob(25);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Config& c : wellPosedConfigs()) {
    CAPTURE(kernelName(c.kernel.type));
    const HrbfModel<3> m = fitHrbf<3>(s, {c.kernel, c.polynomial, 0.0});
    for (int b = 0; b < 5; ++b) {
      Box<3> box;
      box.lo = Vec<3>(-1.2 + u(rng), -1.2 + u(rng), -1.2 + u(rng));
      box.hi = box.lo + Vec<3>::Constant(0.2 + 0.8 * u(rng));
      const double L = m.lipschitzBound(box);
      for (int i = 0; i < 200; ++i) {
        const Vec<3> x = box.lo + (box.hi - box.lo).cwiseProduct(Vec<3>(u(rng), u(rng), u(rng)));
        CHECK(m.gradient(x).norm() <= L * (1 + 1e-12));
      }
    }
  }
}

TEST_CASE("regression: the LU fallback after a failed Cholesky factorises the original matrix") {
  // dpotrf overwrites the diagonal; an early version restored only the strict lower triangle and
  // the fallback solved a different system (residuals 0.08 instead of 1e-7). The coefficients
  // themselves are not compared: the system is so ill-conditioned that the last bits of its
  // assembly move them (an x86-64-v4 build gave coefficient vectors 134 apart, both fits
  // interpolating to 1e-13: the direct solve assembles both triangles, the fallback mirrors the
  // lower one).
  HermiteSamples<3> s = testing::goldenSphere(200);
  const HrbfOptions o{{KernelType::Gaussian, 0.9}, Polynomial::Linear, 0.0, SolverChoice::NullspaceCholesky};
  FitReport rep;
  const HrbfModel<3> fallback = fitHrbf<3>(s, o, &rep);
  REQUIRE(rep.solver == "lu");  // the Cholesky of this ill-conditioned system fails
  HrbfOptions lu = o;
  lu.solver = SolverChoice::Lu;
  const HrbfModel<3> direct = fitHrbf<3>(s, lu);
  const auto residual = [&](const HrbfModel<3>& m) {  // max over the samples of |f| and ‖∇f − n‖
    double r = 0;
    for (int i = 0; i < s.size(); ++i)
      r = std::max({r, std::abs(m.value(s.points.col(i))), (m.gradient(s.points.col(i)) - s.normals.col(i)).norm()});
    return r;
  };
  CAPTURE(residual(direct));
  CHECK(residual(fallback) <= 1e-5);
  CHECK(residual(fallback) <= 10 * residual(direct) + 1e-9);
  const HermiteSamples<3> s2 = testing::goldenSphere(30);
  const HrbfOptions o2{{KernelType::Gaussian, 0.9}, Polynomial::None, 0.0, SolverChoice::Cholesky};
  SaddleSystem sys = assembleHrbf<3>(s2, o2);
  sys.A.diagonal().array() -= 50.0;  // indefinite: the plain Cholesky fails too
  const SaddleSolution a = solveSaddle(sys, SolverChoice::Cholesky);
  const SaddleSolution b = solveSaddle(sys, SolverChoice::Lu);
  CHECK(a.solver == "lu");
  CHECK((a.x - b.x).norm() == 0.0);
}

TEST_CASE("termMagnitude is the sum of the magnitudes of the terms that make up f") {
  // One centre with α, β and a quadratic polynomial, so every term can be written out.
  const Points<2> centre = (Points<2>(2, 1) << 0.2, -0.1).finished();
  const Eigen::VectorXd alpha = (Eigen::VectorXd(1) << 1.5).finished();
  const Points<2> beta = (Points<2>(2, 1) << -0.3, 0.4).finished();
  const Eigen::VectorXd poly = (Eigen::VectorXd(6) << 0.5, -1, 2, 0.25, -0.5, 3).finished();  // 1 x y xx xy yy
  const HrbfModel<2> m(Kernel{KernelType::Cubic, 1.0}, Polynomial::Quadratic, centre, alpha, beta, poly);
  const Vec<2> x(0.7, -0.6);
  const Vec<2> d = x - centre.col(0);
  const double r = d.norm();
  const double expected = std::abs(1.5 * r * r * r) + std::abs(3 * r * d.dot(beta.col(0))) + 0.5 + 0.7 + 1.2 +
                          0.25 * 0.49 + 0.5 * 0.42 + 3 * 0.36;
  CHECK(m.termMagnitude(x) == doctest::Approx(expected).epsilon(1e-14));
  CHECK(m.termMagnitude(x) >= std::abs(m.value(x)));
}
