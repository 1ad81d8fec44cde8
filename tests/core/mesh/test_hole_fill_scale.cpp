// Hole filling at scale: one 2 000-edge non-planar hole, a 100k-triangle mesh with 100 holes,
// progress and cancellation.

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "core/mesh/hole_fill.h"
#include "core/shapes/mesh_shapes.h"
#include "support/mesh_test_shapes.h"
#include "support/timing_slack.h"

using namespace hermite;
using hermite::testing::smallestAngleDegrees;

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("hole filling at scale: a 2 000-edge non-planar hole closes, graded, with progress") {
  const TriMesh holed = openWavySphereMesh(2000, 40, 13, 0.3);
  const std::vector<BoundaryLoop> loops = detectHoles(holed);
  REQUIRE(loops.size() == 1);
  REQUIRE(loops[0].size() == 2000);
  double zLo = 1e9, zHi = -1e9;  // the rim is not planar: its heights spread
  for (int v : loops[0]) zLo = std::min(zLo, holed.vertices(2, v)), zHi = std::max(zHi, holed.vertices(2, v));
  CHECK(zHi - zLo > 0.3);

  HoleFillOptions options;
  std::vector<double> fractions;
  const auto t0 = std::chrono::steady_clock::now();
  auto last = t0;
  double longestGap = 0;  // s between progress calls: how late a cancellation can be seen
  options.progress = [&](double f) {
    longestGap = std::max(longestGap, secondsSince(last));
    last = std::chrono::steady_clock::now();
    return fractions.push_back(f), true;
  };
  const HoleFillResult r = fillHoles(holed, options);
  const double seconds = secondsSince(t0);
  MESSAGE("2 000-edge hole: ", seconds, " s, ", r.trianglesAdded, " triangles added, ", fractions.size(),
          " progress calls, longest gap between them ", longestGap * 1000, " ms, max |f| ", r.maxAbsF,
          ", unconverged ", r.unconverged);
  for (const std::string& m : r.messages) MESSAGE(m);
  CHECK(r.holesFilled == 1);
  CHECK(r.holes[0].method == "min-weight");
  const MeshCheck c = checkMesh(r.mesh);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 2);
  CHECK(smallestAngleDegrees(r.mesh, holed.triangleCount()) >= 1.0);
  // Graded: far fewer than the ≈ 700 000 triangles of the boundary's edge length.
  CHECK(r.trianglesAdded < 100000);
  REQUIRE(fractions.size() >= 10);
  for (std::size_t k = 1; k < fractions.size(); ++k) CHECK(fractions[k] >= fractions[k - 1]);
  CHECK(fractions.back() == doctest::Approx(1.0));
  // A hang guard only (docs/performance.md has the measured time), and as generous a bound on
  // the gaps between reports, for a shared machine; both scaled for a sanitizer build.
  CHECK(seconds < 60 * testing::kTimingSlack);
  CHECK(longestGap < 2.0 * testing::kTimingSlack);
}

TEST_CASE("hole filling at scale: cancelling a large hole stops at once when progress returns false") {
  const TriMesh holed = openWavySphereMesh(2000, 40, 13, 0.3);
  for (double at : {0.05, 0.3, 0.55}) {  // refinement, fairing and fit, projection
    CAPTURE(at);
    HoleFillOptions options;
    std::chrono::steady_clock::time_point refused{};
    bool said = false;
    options.progress = [&](double f) {
      if (f < at) return true;
      if (!said) refused = std::chrono::steady_clock::now(), said = true;
      return false;
    };
    const HoleFillResult r = fillHoles(holed, options);
    REQUIRE(said);
    const double latency = secondsSince(refused);
    MESSAGE("cancelled at ", at, ": returned ", latency * 1000, " ms after progress returned false");
    CHECK(r.cancelled);
    CHECK(r.holesFilled == 0);
    CHECK(r.holes[0].reason == "cancelled");
    CHECK(latency < 1.0);  // generous on a shared machine (an exception unwinds at once)
  }
}

TEST_CASE("hole filling at scale: a 100k-triangle torus with 100 holes closes") {
  // ≈100k triangles, 100 holes of about 10–60 boundary edges.
  const TriMesh holed = holedTorusMesh(316, 158, 20, 5, 0.015, 0.05);
  CHECK(holed.triangleCount() > 90000);
  const std::vector<BoundaryLoop> loops = detectHoles(holed);
  REQUIRE(loops.size() == 100);
  std::size_t fewest = 1000, most = 0;
  for (const BoundaryLoop& l : loops) fewest = std::min(fewest, l.size()), most = std::max(most, l.size());
  MESSAGE("boundary edges per hole: ", fewest, " … ", most);
  const auto t0 = std::chrono::steady_clock::now();
  const HoleFillResult r = fillHoles(holed);
  MESSAGE("100 holes: ", secondsSince(t0), " s, ", r.trianglesAdded, " triangles added");
  for (const std::string& m : r.messages) MESSAGE(m);
  CHECK(r.holesFilled == 100);
  const MeshCheck c = checkMesh(r.mesh);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 0);
  CHECK(smallestAngleDegrees(r.mesh, holed.triangleCount()) >= 1.0);
  CHECK(secondsSince(t0) < 60);  // a hang guard only
}

TEST_CASE("hole filling: a rectangular hole's straight boundary runs leave no sliver (the minimum-weight path)") {
  // Cells i ∈ [10, 22), j ∈ [5, 12) of a 64 × 32 torus grid (cell (i, j) is triangles
  // 2(i·32 + j) and 2(i·32 + j) + 1): four straight runs of equally spaced boundary vertices,
  // the kind of boundary where a midpoint split can land on the corner of a flat triangle.
  const TriMesh holed = hermite::testing::removeTriangles(parametricTorusMesh(64, 32), [](int t) {
    const int cell = t / 2, i = cell / 32, j = cell % 32;
    return i >= 10 && i < 22 && j >= 5 && j < 12;
  });
  HoleFillOptions options;
  options.frontMaxEdges = 0;  // straight to the minimum-weight triangulation
  const HoleFillResult r = fillHoles(holed, options);
  for (const std::string& m : r.messages) MESSAGE(m);
  CHECK(r.holesFilled == 1);
  const MeshCheck c = checkMesh(r.mesh);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 0);
  CHECK(smallestAngleDegrees(r.mesh, holed.triangleCount()) >= 1.0);
}
