// The bordered refit of a dragged sample (core/rbf/hrbf_bordered_refit.h) against fitting from scratch.
#include <doctest/doctest.h>

#include <vector>

#include "core/base/errors.h"
#include "core/rbf/hrbf_bordered_refit.h"
#include "support/test_data.h"

using namespace hermite;
using namespace hermite::testing;

namespace {

// max |f_a − f_b| and max ‖∇f_a − ∇f_b‖ over probes, relative to max |f_b| and max ‖∇f_b‖.
template <int Dim>
std::pair<double, double> relativeDifference(const RadialSum<Dim>& a, const RadialSum<Dim>& b, const Points<Dim>& X) {
  Eigen::VectorXd fa, fb;
  Points<Dim> ga, gb;
  a.evaluateBatch(X, fa, &ga);
  b.evaluateBatch(X, fb, &gb);
  const double df = (fa - fb).cwiseAbs().maxCoeff() / std::max(fb.cwiseAbs().maxCoeff(), 1e-300);
  const double dg = (ga - gb).colwise().norm().maxCoeff() / std::max(gb.colwise().norm().maxCoeff(), 1e-300);
  return {df, dg};
}

template <int Dim>
Points<Dim> probes(const HermiteSamples<Dim>& s, int count) {
  Points<Dim> X(Dim, count);
  const Vec<Dim> lo = s.points.rowwise().minCoeff().array() - 0.3, hi = s.points.rowwise().maxCoeff().array() + 0.3;
  for (int k = 0; k < count; ++k) {
    Vec<Dim> u;
    for (int d = 0; d < Dim; ++d) u(d) = std::fmod(0.6180339887 * (k + 1) * (d + 2) + 0.1 * d, 1.0);
    X.col(k) = lo + (hi - lo).cwiseProduct(u);
  }
  return X;
}

template <int Dim>
void checkAgainstScratch(const HermiteSamples<Dim>& samples, const HrbfOptions& options, int moved,
                         const Vec<Dim>& point, const Vec<Dim>& normal) {
  CAPTURE(kernelName(options.kernel.type));
  CAPTURE(polynomialName(options.polynomial));
  CAPTURE(options.smoothing);
  const HrbfBorderedRefit<Dim> drag(samples, options, moved);
  FitReport dragReport;
  const HrbfModel<Dim> fast = drag.fit(point, normal, &dragReport);
  HermiteSamples<Dim> edited = samples;
  edited.points.col(moved) = point;
  edited.normals.col(moved) = normal.normalized();
  HrbfOptions lu = options;
  lu.solver = SolverChoice::Lu;  // its condition estimate is of the same matrix K
  FitReport scratchReport;
  const HrbfModel<Dim> scratch = fitHrbf<Dim>(edited, lu, &scratchReport);

  // Two backward-stable solves of one system differ by about κ·ε in the forward error.
  const double tolerance = std::max(1e-11, 100 * 2.2e-16 * scratchReport.conditionEstimate);
  CAPTURE(tolerance);
  const auto [df, dg] = relativeDifference<Dim>(fast, scratch, probes(edited, 400));
  CHECK(df < tolerance);
  CHECK(dg < tolerance);
  if (options.smoothing == 0) {  // it interpolates the moved sample: f = 0 and ∇f = n there
    Vec<Dim> g;
    const double f = fast.evaluate(point, &g);
    CHECK(std::abs(f) < 1e-9);
    CHECK((g - normal.normalized()).norm() < 1e-9);
  }
  CHECK(dragReport.solver == "bordered-lu");
  CHECK(dragReport.nUnknowns == scratchReport.nUnknowns);
  // Two estimates of κ₁(K) (dlacn2 through bordered solves, dgecon on the LU): same order.
  CAPTURE(dragReport.conditionEstimate);
  CAPTURE(scratchReport.conditionEstimate);
  CHECK(dragReport.conditionEstimate > scratchReport.conditionEstimate / 10);
  CHECK(dragReport.conditionEstimate < scratchReport.conditionEstimate * 10);
}

}  // namespace

TEST_CASE("a dragged sample's bordered refit equals the fit from scratch, in 2D and 3D") {
  const HermiteSamples<2> curve = ellipse(40);
  // Condition numbers (LU's estimate) 1e5–1e8, and one smoothing fit.
  const std::vector<HrbfOptions> options2{{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0},
                                          {{KernelType::Gaussian, 0.15}, Polynomial::None, 0.0},
                                          {{KernelType::Wendland, 1.5}, Polynomial::Quadratic, 0.0},
                                          {{KernelType::Polyharmonic, 1.0}, Polynomial::Quadratic, 0.0},
                                          {{KernelType::Cubic, 1.0}, Polynomial::Linear, 1e-3}};
  for (const HrbfOptions& o : options2)
    for (int moved : {0, 17, 39})
      checkAgainstScratch<2>(curve, o, moved, curve.points.col(moved) + Vec<2>(0.13, -0.07),
                             Vec<2>(curve.normals.col(moved)) + Vec<2>(0.3, 0.2));

  const HermiteSamples<3> blobby = blob(60);
  for (const HrbfOptions& o : {HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0},
                               HrbfOptions{{KernelType::Gaussian, 0.3}, Polynomial::Linear, 0.0}})
    checkAgainstScratch<3>(blobby, o, 31, blobby.points.col(31) + Vec<3>(0.05, 0.1, -0.08),
                           Vec<3>(0.2, -1.0, 0.4));
}

TEST_CASE("one factorisation serves a whole drag: successive moves each equal their fit from scratch") {
  const HermiteSamples<2> curve = ellipse(30);
  const HrbfOptions o{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  const HrbfBorderedRefit<2> drag(curve, o, 5);
  for (int step = 1; step <= 6; ++step) {
    const Vec<2> p = curve.points.col(5) + step * Vec<2>(0.04, 0.03);
    const HrbfModel<2> fast = drag.fit(p, curve.normals.col(5));
    HermiteSamples<2> edited = curve;
    edited.points.col(5) = p;
    const auto [df, dg] = relativeDifference<2>(fast, fitHrbf<2>(edited, o), probes(edited, 200));
    CHECK(df < 1e-9);
    CHECK(dg < 1e-9);
  }
}

TEST_CASE("a drag onto another sample is reported as a singular system, as fitting from scratch reports it") {
  const HermiteSamples<2> curve = ellipse(24);
  const HrbfBorderedRefit<2> drag(curve, {{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0}, 3);
  // Same point as sample 8: its value and gradient conditions appear twice. Rounding keeps the
  // pivots from being exactly zero, so (like LU from scratch) the report says why: the estimate.
  FitReport report;
  drag.fit(curve.points.col(8), Vec<2>(1.0, 0.0), &report);
  CHECK(report.conditionEstimate > 1e15);
  bool warned = false;
  for (const std::string& w : report.warnings) warned = warned || w.find("ill-conditioned") != std::string::npos;
  CHECK(warned);
  CHECK_THROWS_AS(drag.fit(Vec<2>(0.1, 0.2), Vec<2>::Zero()), InputError);
  CHECK_THROWS_AS(HrbfBorderedRefit<2>(curve, {{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0}, 24), InputError);
}
