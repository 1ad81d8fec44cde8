// The data reach of a global fit of a data file (scene/data_reach_mask.h): an open scan's surface
// ends near its samples instead of following the global interpolant to view.bounds, while
// preset, inline and hand-made data keep their whole zero set.

#include <doctest/doctest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "scene/data_file_scene.h"
#include "scene/data_reach_mask.h"
#include "scene/degenerate_check.h"
#include "scene/view_bounds.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// The samples of a unit sphere with z ≥ zMin, as "x y z nx ny nz" lines.
std::string capText(int sphereSamples, double zMin, int* count) {
  const HermiteSamples<3> s = testing::goldenSphere(sphereSamples);
  std::string text;
  char line[160];
  *count = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (s.points(2, i) < zMin) continue;
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", s.points(0, i), s.points(1, i),
                  s.points(2, i), s.normals(0, i), s.normals(1, i), s.normals(2, i));
    text += line;
    ++*count;
  }
  return text;
}

SceneFit<3> maskedFit(const Scene& scene) {
  SceneFit<3> fit = fitScene<3>(scene);
  checkDegenerateField<3>(scene, fit);
  maskBeyondDataReach<3>(scene, fit);
  return fit;
}

// The largest distance from a vertex of `mesh` to the nearest of `points`.
double farthestFromData(const TriMesh& mesh, const Points<3>& points) {
  double worst = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v)
    worst = std::max(worst, (points.colwise() - mesh.vertices.col(v)).colwise().norm().minCoeff());
  return worst;
}

}  // namespace

TEST_CASE("data reach mask: a global fit of an open scan's file ends near its samples, its values untouched") {
  const testing::TempDir dir;
  int count = 0;
  const std::string path = dir.write("cap.xyzn", capText(4000, 0.5, &count));
  const Scene scene = dataFileScene(path).scene;
  const SceneFit<3> fit = maskedFit(scene);
  REQUIRE(fit.pu() == nullptr);  // 1 000 samples: a global fit
  CHECK(dataReachApplies<3>(scene, fit));
  REQUIRE(fit.masked);
  CHECK_FALSE(fit.field().everywhereValid());
  for (int i = 0; i < fit.data.size(); i += 37) {
    const Vec<3> p = fit.data.points.col(i);
    CHECK(fit.field().value(p) == fit.unmaskedField().value(p));
    CHECK(fit.field().valid(p));
  }
  CHECK_FALSE(fit.field().valid(Vec<3>(0, 0, -1)));  // the far pole: no data
  MarchingOptions o;
  o.resolution = 48;
  const Box<3> bounds = viewBounds<3>(scene.view, fit.data.points);
  const TriMesh whole = marchingCubes(fit.unmaskedField(), bounds, o);
  const TriMesh cut = marchingCubes(fit.field(), bounds, o);
  const double wholeFar = farthestFromData(whole, fit.data.points), cutFar = farthestFromData(cut, fit.data.points);
  MESSAGE("spherical cap of " << count << " samples: farthest vertex from the data " << wholeFar << " unmasked, "
                           << cutFar << " masked");
  CHECK(wholeFar > 0.45);  // the global interpolant closes the cap: 0.49 from the data
  // The zero-set reach: 2 capped spacings (at most twice the median 6th-neighbour distance, 0.07).
  CHECK(cutFar < 0.35);
  const MeshCheck check = checkMesh(cut);
  CHECK(check.components == 1);
  CHECK(check.boundaryEdges > 0);  // open at the rim, as the scan is
}

TEST_CASE("data reach mask: presets, inline data, hand-made files and PU fits are left as they are, unless asked") {
  const testing::TempDir dir;
  int count = 0;
  const std::string small = dir.write("cap.xyzn", capText(100, 0.6, &count));
  REQUIRE(count < kReachMinSamples);
  const Scene handMade = dataFileScene(small).scene;
  CHECK_FALSE(maskedFit(handMade).masked);

  const std::string big = dir.write("hemisphere.xyzn", capText(1200, 0.0, &count));
  const Scene pu = dataFileScene(big, {"fit.partition.enabled=true"}).scene;
  const SceneFit<3> puFit = maskedFit(pu);
  REQUIRE(puFit.pu() != nullptr);
  CHECK_FALSE(dataReachApplies<3>(pu, puFit));
  CHECK_FALSE(puFit.masked);  // the partition of unity has its own reach

  const Scene off = dataFileScene(big, {"fit.reach_mask=false"}).scene;
  CHECK(off.fit.reachMask == AutoSwitch::Off);
  CHECK_FALSE(maskedFit(off).masked);

  Scene preset = pu;
  preset.data = DataSpec{};
  preset.data.preset = "sphere";
  preset.data.count = 1000;
  preset.fit.partition.enabled = PartitionSwitch::Off;
  CHECK_FALSE(maskedFit(preset).masked);
  preset.fit.reachMask = AutoSwitch::On;  // asked for: any global fit
  const SceneFit<3> asked = maskedFit(preset);
  REQUIRE(asked.masked);
  CHECK_FALSE(asked.field().valid(Vec<3>(0, 0, 0)));  // the centre of the sphere is far from its samples
  CHECK(asked.field().valid(asked.data.points.col(0)));

  Scene inlineData = preset;
  inlineData.fit.reachMask = AutoSwitch::Auto;
  inlineData.data = DataSpec{};
  const HermiteSamples<3> s = testing::goldenSphere(120);
  for (int i = 0; i < s.size(); ++i) {
    inlineData.data.points.push_back({s.points(0, i), s.points(1, i), s.points(2, i)});
    inlineData.data.normals.push_back({s.normals(0, i), s.normals(1, i), s.normals(2, i)});
  }
  CHECK_FALSE(maskedFit(inlineData).masked);
}
