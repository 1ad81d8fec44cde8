// The leave-one-out closed form against its definition (N refits), and the radius sweep.

#include <doctest/doctest.h>

#include <cmath>

#include "core/base/errors.h"
#include "core/rbf/leave_one_out.h"
#include "scene/radius_sweep.h"
#include "scene/scene_file.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

template <int Dim>
void checkAgainstBruteForce(const HermiteSamples<Dim>& s, const HrbfOptions& o) {
  const LeaveOneOutResult fast = hrbfLeaveOneOut<Dim>(s, o);
  const LeaveOneOutResult slow = hrbfLeaveOneOutBruteForce<Dim>(s, o);
  REQUIRE(fast.valueError.size() == slow.valueError.size());
  double scale = 1e-3;
  for (std::size_t i = 0; i < fast.valueError.size(); ++i)
    scale = std::max({scale, slow.valueError[i], slow.gradientError[i]});
  for (std::size_t i = 0; i < fast.valueError.size(); ++i) {
    CHECK(fast.valueError[i] == doctest::Approx(slow.valueError[i]).epsilon(1e-6).scale(scale));
    CHECK(fast.gradientError[i] == doctest::Approx(slow.gradientError[i]).epsilon(1e-6).scale(scale));
  }
  CHECK(fast.combined == doctest::Approx(slow.combined).epsilon(1e-6));
}

}  // namespace

TEST_CASE("leave-one-out closed form equals N refits (3D, several kernels and polynomials)") {
  const HermiteSamples<3> s = testing::goldenSphere(24, 0.8);
  for (auto [kernel, radius, poly] : {std::tuple{KernelType::Cubic, 1.0, Polynomial::Linear},
                                      std::tuple{KernelType::Gaussian, 0.7, Polynomial::None},
                                      std::tuple{KernelType::Wendland, 1.5, Polynomial::Linear},
                                      std::tuple{KernelType::Polyharmonic, 1.0, Polynomial::Quadratic}}) {
    CAPTURE(kernelName(kernel));
    HrbfOptions o;
    o.kernel = Kernel{kernel, radius};
    o.polynomial = poly;
    checkAgainstBruteForce<3>(s, o);
  }
}

TEST_CASE("leave-one-out closed form equals N refits (2D, with smoothing)") {
  const HermiteSamples<2> s = testing::ellipse(16);
  HrbfOptions o;
  o.kernel = Kernel{KernelType::InverseMultiquadric, 0.5};
  o.polynomial = Polynomial::Linear;
  o.smoothing = 1e-3;
  checkAgainstBruteForce<2>(s, o);
}

TEST_CASE("leave-one-out is zero where the data are reproduced exactly") {
  // Quadratic + polyharmonic reproduces a sphere: every reduced fit still does.
  const HermiteSamples<3> s = testing::goldenSphere(30);
  HrbfOptions o;
  o.kernel = Kernel{KernelType::Polyharmonic, 1.0};
  o.polynomial = Polynomial::Quadratic;
  const LeaveOneOutResult r = hrbfLeaveOneOut<3>(s, o);
  CHECK(r.maxValue < 1e-8);
  // ∇(|x|²−1)/2 = x = n on the unit sphere: the reproduced f has the data's gradient.
  CHECK(r.maxGradient < 1e-7);
}

TEST_CASE("log-spaced radii and the --radii argument") {
  const std::vector<double> r = logSpacedRadii(0.1, 10, 5);
  REQUIRE(r.size() == 5);
  CHECK(r[0] == 0.1);
  CHECK(r[2] == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(r[4] == 10.0);
  CHECK(parseRadiiArgument("0.05:2:8").size() == 8);
  CHECK_THROWS_AS(parseRadiiArgument("0.05:2"), UsageError);
  CHECK_THROWS_AS(parseRadiiArgument("2:0.05:3"), UsageError);
  CHECK_THROWS_AS(parseRadiiArgument("a:1:3"), UsageError);
  CHECK_THROWS_AS(parseRadiiArgument("0:1:3"), UsageError);
}

TEST_CASE("radius sweep: rows per radius, failures as rows, the suggestion is the cleanest candidate with the least LOO error") {
  Scene scene;
  scene.mode = SceneMode::Implicit2d;
  scene.data.preset = "curve2d";
  scene.data.count = 40;
  scene.fit.kernel = KernelType::Gaussian;
  scene.fit.polynomial = Polynomial::None;
  const std::vector<double> radii = logSpacedRadii(0.05, 3, 6);
  const auto rows = sweepRadii<2>(scene, radii);
  REQUIRE(rows.size() == radii.size());
  int ok = 0;
  for (const RadiusSweepRow& row : rows) {
    CAPTURE(row.radius);
    if (!row.ok()) continue;
    ++ok;
    CHECK(row.conditionEstimate > 0);
    // Leave-one-out is defined wherever the system is not numerically singular.
    if (row.conditionEstimate < 1e12) CHECK(std::isfinite(row.looCombined));
    if (!std::isfinite(row.looCombined)) CHECK(!row.looError.empty());
  }
  CHECK(ok == int(rows.size()));  // ill-conditioned fits still fit (with a warning)
  // The condition estimate grows with r for the gaussian (flatter kernels: nearly dependent columns).
  CHECK(rows[1].conditionEstimate < rows[4].conditionEstimate);
  const int best = suggestedRadiusIndex(rows);
  REQUIRE(best >= 0);
  CHECK(rows[best].rejection().empty());
  CHECK(rows[best].conditionEstimate <= kSuggestionMaxCondition);
  for (const RadiusSweepRow& row : rows) {
    CAPTURE(row.radius);
    CHECK(row.validation == "leave-one-out");
    CHECK(row.components >= 0);
    if (!row.rejection().empty()) continue;
    CHECK(rows[best].defects() <= row.defects());
    if (row.defects() == rows[best].defects()) CHECK(rows[best].looCombined <= row.looCombined);
  }
  const std::string csv = radiusSweepCsv(rows);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == int(rows.size()) + 1);

  std::atomic<bool> cancel{true};
  CHECK(sweepRadii<2>(scene, radii, &cancel).empty());
}
