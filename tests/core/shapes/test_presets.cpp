#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <string>

#include "core/base/errors.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/bunny_data.h"
#include "core/shapes/presets.h"

using namespace hermite;

namespace {

template <typename F>
std::string thrownMessage(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Counts used for every preset: its own (0), its suggested ones and a few odd ones.
std::vector<int> testedCounts(const PresetInfo& info) {
  std::vector<int> counts{0};
  counts.insert(counts.end(), info.suggestedCounts.begin(), info.suggestedCounts.end());
  if (info.minCount < info.maxCount) {
    counts.push_back(info.minCount);
    counts.push_back(info.minCount + 7);
    counts.push_back(std::min(info.maxCount, 1001));
  }
  return counts;
}

template <int Dim>
HermiteSamples<Dim> makePreset(const std::string& name, int count) {
  if constexpr (Dim == 2) {
    return makePreset2d(name, count);
  } else {
    return makePreset3d(name, count);
  }
}

// Smallest distance between two samples (O(N²): the tested counts are small).
template <int Dim>
double minimumSpacing(const Points<Dim>& P) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < P.cols(); ++i) {
    for (Eigen::Index j = i + 1; j < P.cols(); ++j) best = std::min(best, (P.col(i) - P.col(j)).norm());
  }
  return best;
}

template <int Dim>
void checkCommonInvariants(const PresetInfo& info) {
  for (int count : testedCounts(info)) {
    CAPTURE(info.name);
    CAPTURE(count);
    const HermiteSamples<Dim> s = makePreset<Dim>(info.name, count);
    const int expected = count == 0 ? info.defaultCount : count;
    REQUIRE(s.size() == expected);
    REQUIRE(s.normals.cols() == expected);
    CHECK(s.points.allFinite());
    CHECK(s.normals.allFinite());
    CHECK((s.normals.colwise().norm().array() - 1.0).abs().maxCoeff() <= 1e-12);
    CHECK(s.points.colwise().norm().maxCoeff() <= 1.0 + 1e-12);
    CHECK(minimumSpacing<Dim>(s.points) > 1e-6);
    // Determinism: a second call gives identical doubles.
    const HermiteSamples<Dim> again = makePreset<Dim>(info.name, count);
    CHECK(s.points == again.points);
    CHECK(s.normals == again.normals);
  }
}

// Largest angle-free mismatch between unit normals and normalised gradients of `field`, and
// largest |f| at the samples.
template <int Dim>
std::pair<double, double> fieldMismatch(const HermiteSamples<Dim>& s, const ImplicitField<Dim>& field) {
  double normalError = 0;
  double valueError = 0;
  for (int i = 0; i < s.size(); ++i) {
    Vec<Dim> g;
    const double f = field.evaluate(s.points.col(i), &g);
    valueError = std::max(valueError, std::abs(f));
    normalError = std::max(normalError, (g.normalized() - s.normals.col(i)).norm());
  }
  return {normalError, valueError};
}

}  // namespace

TEST_CASE("presets: the table is consistent") {
  std::set<std::string> names;
  for (const PresetInfo& info : allPresets()) {
    CAPTURE(info.name);
    CHECK(names.insert(info.name).second);
    CHECK((info.dimension == 2 || info.dimension == 3));
    CHECK(info.minCount <= info.defaultCount);
    CHECK(info.defaultCount <= info.maxCount);
    for (int c : info.suggestedCounts) CHECK((c >= info.minCount && c <= info.maxCount));
    CHECK(!info.description.empty());
    CHECK(&presetInfo(info.name) == &info);
  }
  for (const char* name : {"sphere6", "sphere", "torus", "two-tori", "bunny", "curve2d", "circle"}) {
    CHECK(names.count(name) == 1);
  }
  CHECK(presetInfo("two-tori").suggestedCounts == std::vector<int>{120, 400});
  CHECK(presetInfo("two-tori").defaultCount == 400);
  CHECK(presetInfo("curve2d").suggestedCounts == std::vector<int>{40, 80, 200, 400});
  CHECK(presetInfo("curve2d").defaultCount == 80);
  CHECK(presetInfo("sphere").minCount == 4);
  CHECK(presetInfo("sphere").maxCount == 10'000'000);
}

TEST_CASE("presets: counts, unit normals, unit ball, no duplicates, determinism") {
  for (const PresetInfo& info : allPresets()) {
    if (info.dimension == 2) {
      checkCommonInvariants<2>(info);
    } else {
      checkCommonInvariants<3>(info);
    }
  }
}

TEST_CASE("presets: sphere6 is the six axis points of the unit sphere") {
  const HermiteSamples<3> s = makePreset3d("sphere6", 0);
  REQUIRE(s.size() == 6);
  CHECK(s.points == s.normals);
  CHECK(s.points.rowwise().sum().norm() == 0.0);
  for (int i = 0; i < 6; ++i) {
    CHECK(s.points.col(i).norm() == 1.0);
    CHECK(s.points.col(i).cwiseAbs().maxCoeff() == 1.0);
  }
  CHECK(makePreset3d("sphere6", 6).points == s.points);
}

TEST_CASE("presets: sphere and circle samples lie on the unit sphere / circle with radial normals") {
  const SphereField sphere;
  for (int count : {4, 100, 1000}) {
    CAPTURE(count);
    const HermiteSamples<3> s = makePreset3d("sphere", count);
    const auto [normalError, valueError] = fieldMismatch(s, sphere);
    CHECK(normalError <= 1e-9);
    CHECK(valueError <= 1e-12);
    // Fibonacci points: the centroid is near the centre, the bounding box centred.
    CHECK(s.points.rowwise().mean().norm() < 2.0 / count);
    if (count >= 100) CHECK(boundingBox<3>(s.points).center().norm() < 0.05);
  }
  // Well spread: nearest neighbours at least half the spacing of an ideal hexagonal cover.
  const HermiteSamples<3> s = makePreset3d("sphere", 1000);
  const double ideal = std::sqrt(4.0 * std::numbers::pi / 1000 / (std::sqrt(3.0) / 2.0));
  CHECK(minimumSpacing<3>(s.points) > 0.5 * ideal);

  const CircleField circle;
  for (int count : {3, 16, 1000}) {
    CAPTURE(count);
    const HermiteSamples<2> c = makePreset2d("circle", count);
    const auto [normalError, valueError] = fieldMismatch(c, circle);
    CHECK(normalError <= 1e-9);
    CHECK(valueError <= 1e-12);
    CHECK(c.points.rowwise().mean().norm() < 1e-12);
  }
}

TEST_CASE("presets: torus samples lie on the analytic torus with its gradient as normal") {
  const std::vector<TorusGeometry> tori = presetTori("torus");
  REQUIRE(tori.size() == 1);
  CHECK(tori[0].major + tori[0].minor == doctest::Approx(1.0).epsilon(1e-15));
  const TorusField field(tori[0].centre, tori[0].major, tori[0].minor, tori[0].axis);
  for (int count : {4, 200, 1000}) {
    CAPTURE(count);
    const HermiteSamples<3> s = makePreset3d("torus", count);
    const auto [normalError, valueError] = fieldMismatch(s, field);
    CHECK(normalError <= 1e-9);
    CHECK(valueError <= 1e-12);
  }
  const HermiteSamples<3> s = makePreset3d("torus", 200);
  CHECK(boundingBox<3>(s.points).center().norm() < 0.05);
  CHECK(s.points.rowwise().mean().norm() < 0.02);
  // Well spread: nearest neighbours at least 3/4 of the ideal hexagonal spacing.
  const double area = 4.0 * std::numbers::pi * std::numbers::pi * tori[0].major * tori[0].minor;
  for (int count : {60, 200, 1000}) {
    CAPTURE(count);
    const double ideal = std::sqrt(area / count / (std::sqrt(3.0) / 2.0));
    CHECK(minimumSpacing<3>(makePreset3d("torus", count).points) > 0.75 * ideal);
  }
  // Area-uniform: with density ∝ R + r cos v, the mean of q − R = r cos v is r²/(2R)
  // (q = distance to the axis); a density uniform in (u, v) would give 0.
  const double meanOffset = (s.points.topRows<2>().colwise().norm().array() - tori[0].major).mean();
  CHECK(std::abs(meanOffset - tori[0].minor * tori[0].minor / (2 * tori[0].major)) < 0.005);
}

TEST_CASE("presets: two-tori are interlinked, disjoint, centred, each sample on its torus") {
  const std::vector<TorusGeometry> tori = presetTori("two-tori");
  REQUIRE(tori.size() == 2);
  const TorusField a(tori[0].centre, tori[0].major, tori[0].minor, tori[0].axis);
  const TorusField b(tori[1].centre, tori[1].major, tori[1].minor, tori[1].axis);
  // Each core circle passes through the other torus's centre (interlinked), and the tubes are
  // apart: the core circles are R apart at their closest, R > 2r.
  CHECK(std::abs(a.evaluate(tori[1].centre) + tori[0].minor) < 1e-15);
  CHECK(std::abs(b.evaluate(tori[0].centre) + tori[1].minor) < 1e-15);
  CHECK(tori[0].major > 2 * tori[0].minor);
  // Farthest surface point: along −x on the first torus.
  CHECK(std::abs(tori[0].centre.x()) + tori[0].major + tori[0].minor == doctest::Approx(1.0).epsilon(1e-15));
  CHECK((tori[0].centre + tori[1].centre).norm() == 0.0);

  for (int count : {8, 120, 400, 401}) {
    CAPTURE(count);
    const HermiteSamples<3> s = makePreset3d("two-tori", count);
    int onA = 0;
    int onB = 0;
    double normalError = 0;
    for (int i = 0; i < s.size(); ++i) {
      Vec<3> ga;
      Vec<3> gb;
      const double fa = a.evaluate(s.points.col(i), &ga);
      const double fb = b.evaluate(s.points.col(i), &gb);
      // On one torus, clearly outside the other.
      const bool isA = std::abs(fa) <= 1e-12 && fb > 0.1;
      const bool isB = std::abs(fb) <= 1e-12 && fa > 0.1;
      CHECK((isA || isB));
      onA += isA ? 1 : 0;
      onB += isB ? 1 : 0;
      normalError = std::max(normalError, ((isA ? ga : gb).normalized() - s.normals.col(i)).norm());
    }
    CHECK(normalError <= 1e-9);
    CHECK(onA == (count + 1) / 2);
    CHECK(onB == count / 2);
  }
  const HermiteSamples<3> s = makePreset3d("two-tori", 400);
  CHECK(boundingBox<3>(s.points).center().norm() < 0.05);
}

TEST_CASE("presets: curve2d is uniform in arc length with exact outward normals") {
  const Curve2dFrame& frame = curve2dFrame();
  CHECK(frame.scale > 0);
  // r(θ) = 1 + 0.35 cos 3θ: the bounding box is symmetric in y; in x it spans [x(2π/3 ± …), 1.35].
  CHECK(std::abs(frame.centre.y()) < 1e-12);
  CHECK(frame.centre.x() > 0.2);
  CHECK(frame.centre.x() < 0.3);

  for (int count : {3, 40, 80, 200, 400}) {
    CAPTURE(count);
    const HermiteSamples<2> s = makePreset2d("curve2d", count);
    double valueError = 0;
    double normalError = 0;
    for (int i = 0; i < s.size(); ++i) {
      // Back to the polar frame: F(y) = ‖y‖ − r(θ), ∇F = ρ̂ − r′(θ)/ρ·θ̂ (same direction in x).
      const Vec<2> y = s.points.col(i) / frame.scale + frame.centre;
      const double rho = y.norm();
      const double theta = std::atan2(y.y(), y.x());
      const double dr = -3.0 * 0.35 * std::sin(3.0 * theta);
      const Vec<2> radial = y / rho;
      const Vec<2> angular(-radial.y(), radial.x());
      valueError = std::max(valueError, std::abs(rho - curve2dRadius(theta)));
      normalError = std::max(normalError, ((radial - dr / rho * angular).normalized() - s.normals.col(i)).norm());
    }
    CHECK(valueError <= 1e-12);
    CHECK(normalError <= 1e-9);
  }

  // Arc-length uniformity: consecutive chords agree to the chord/arc difference O(h³κ²).
  const HermiteSamples<2> s = makePreset2d("curve2d", 400);
  double shortest = 1e300;
  double longest = 0;
  for (int i = 0; i < s.size(); ++i) {
    const double chord = (s.points.col((i + 1) % s.size()) - s.points.col(i)).norm();
    shortest = std::min(shortest, chord);
    longest = std::max(longest, chord);
  }
  CHECK(longest / shortest < 1.001);
  // Fills the unit disc: the farthest sample is at distance ≈ 1, the bounding box is centred.
  CHECK(s.points.colwise().norm().maxCoeff() > 0.999);
  CHECK(boundingBox<2>(s.points).center().norm() < 1e-3);

  // Non-convex: the turning direction of consecutive chords changes sign.
  int leftTurns = 0;
  int rightTurns = 0;
  for (int i = 0; i < s.size(); ++i) {
    const Vec<2> e0 = s.points.col((i + 1) % s.size()) - s.points.col(i);
    const Vec<2> e1 = s.points.col((i + 2) % s.size()) - s.points.col((i + 1) % s.size());
    const double turn = e0.x() * e1.y() - e0.y() * e1.x();
    (turn > 0 ? leftTurns : rightTurns) += 1;
  }
  CHECK(leftTurns > 0);
  CHECK(rightTurns > 0);
}

TEST_CASE("presets: bunny is the embedded mesh, sub-samples are nested farthest-point samples") {
  const HermiteSamples<3> full = makePreset3d("bunny", 0);
  REQUIRE(full.size() == 1839);
  CHECK(presetInfo("bunny").defaultCount == 1839);
  CHECK(presetInfo("bunny").maxCount == 1839);
  CHECK(makePreset3d("bunny", 1839).points == full.points);

  // The embedded copy is the file in the source tree (a stale build would differ).
  std::ifstream file(std::string(HERMITE_SOURCE_DIR) + "/assets/bunny/bunny.xyzn", std::ios::binary);
  REQUIRE(file.good());
  std::stringstream text;
  text << file.rdbuf();
  CHECK(text.str() == embeddedBunnyXyzn());

  // Centred at the bounding-box centre, farthest vertex at distance 1.
  CHECK(boundingBox<3>(full.points).center().norm() < 1e-12);
  CHECK(full.points.colwise().norm().maxCoeff() == doctest::Approx(1.0).epsilon(1e-12));
  // Outward normals: the divergence theorem with F = x gives 3·volume = ∮ x·n dA > 0, and
  // (per vertex, unweighted) the normals point away from the centroid on the whole.
  const Vec<3> centroid = full.points.rowwise().mean();
  double flux = 0;
  for (int i = 0; i < full.size(); ++i) flux += (full.points.col(i) - centroid).dot(full.normals.col(i));
  CHECK(flux / full.size() > 0.2);

  const HermiteSamples<3> s600 = makePreset3d("bunny", 600);
  const HermiteSamples<3> s64 = makePreset3d("bunny", 64);
  CHECK(s600.points.leftCols(64) == s64.points);
  CHECK(s600.normals.leftCols(64) == s64.normals);
  // Every sub-sampled point is a mesh vertex with its exact normal.
  for (int i = 0; i < s600.size(); ++i) {
    bool found = false;
    for (int j = 0; j < full.size() && !found; ++j) {
      found = full.points.col(j) == s600.points.col(i) && full.normals.col(j) == s600.normals.col(i);
    }
    CHECK(found);
  }
  // Well spread: farthest-point sampling keeps every pair at least the covering radius apart,
  // so the 64 samples are much farther apart than 64 arbitrary vertices would be.
  CHECK(minimumSpacing<3>(s64.points) > 0.15);
  CHECK(minimumSpacing<3>(s600.points) > 0.03);
}

TEST_CASE("presets: bad names, dimensions and counts are InputErrors with the valid choices") {
  std::string m = thrownMessage([] { makePreset3d("teapot", 0); });
  CHECK(contains(m, "teapot"));
  CHECK(contains(m, "sphere6"));
  CHECK(contains(m, "two-tori"));
  CHECK(contains(m, "bunny"));
  m = thrownMessage([] { makePreset2d("teapot", 0); });
  CHECK(contains(m, "curve2d"));
  CHECK(contains(m, "circle"));
  m = thrownMessage([] { presetInfo("teapot"); });
  CHECK(contains(m, "sphere6"));
  CHECK(contains(m, "curve2d"));

  m = thrownMessage([] { makePreset2d("sphere", 0); });
  CHECK(contains(m, "3D"));
  CHECK(contains(m, "curve2d"));
  m = thrownMessage([] { makePreset3d("curve2d", 40); });
  CHECK(contains(m, "2D"));
  CHECK(contains(m, "torus"));

  m = thrownMessage([] { makePreset3d("sphere6", 5); });
  CHECK(contains(m, "count 5"));
  CHECK(contains(m, "or 6"));
  m = thrownMessage([] { makePreset3d("sphere", 3); });
  CHECK(contains(m, "[4, 10000000]"));
  CHECK_THROWS_AS(makePreset3d("sphere", 10'000'001), InputError);
  CHECK_THROWS_AS(makePreset3d("sphere", -1), InputError);
  m = thrownMessage([] { makePreset3d("bunny", 1840); });
  CHECK(contains(m, "[4, 1839]"));
  CHECK_THROWS_AS(makePreset3d("bunny", 3), InputError);
  CHECK_THROWS_AS(makePreset3d("two-tori", 7), InputError);
  CHECK_THROWS_AS(makePreset2d("curve2d", 2), InputError);
  CHECK_THROWS_AS(makePreset2d("circle", -5), InputError);
  CHECK_THROWS_AS(presetTori("sphere"), InputError);
}
