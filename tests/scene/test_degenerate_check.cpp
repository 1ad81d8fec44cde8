// Degenerate teaching scenes (issue 19 item 3): warned with cause and remedy, flat regions masked
// so that meshing never closes a surface over noise; well-posed scenes are not warned.

#include <doctest/doctest.h>

#include <string>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "scene/degenerate_check.h"
#include "scene/scene_file.h"
#include "scene/view_bounds.h"

using namespace hermite;

namespace {

SceneFit<3> checkedFit(const std::string& name) {
  const Scene scene = loadSceneFile(std::string(HERMITE_SOURCE_DIR) + "/assets/scenes/" + name);
  SceneFit<3> fit = fitScene<3>(scene);
  checkDegenerateField<3>(scene, fit);
  return fit;
}

bool warnsDegenerate(const SceneFit<3>& fit) {
  for (const std::string& w : fit.warnings)
    if (w.rfind(kDegenerateFieldWarningStart, 0) == 0 && w.find("add a polynomial or increase r") != std::string::npos)
      return true;
  return false;
}

}  // namespace

TEST_CASE("degenerate check: the degenerate teaching scenes are warned and their flat regions masked") {
  for (const char* name : {"wendland_sphere6_r1_none.json", "wendland_twotori_120pts_r0.6_none.json"}) {
    CAPTURE(name);
    const Scene scene = loadSceneFile(std::string(HERMITE_SOURCE_DIR) + "/assets/scenes/" + name);
    const SceneFit<3> fit = checkedFit(name);
    REQUIRE(fit.degenerateField);
    CHECK(fit.degenerateField->degenerate);
    CHECK(fit.degenerateField->flatFraction > 0.25);
    CHECK(warnsDegenerate(fit));
    REQUIRE(fit.masked);
    CHECK_FALSE(fit.field().everywhereValid());
    // The field's values are untouched: the samples are still interpolated.
    CHECK(std::abs(fit.field().value(fit.data.points.col(0))) < 1e-9);
    MarchingOptions o;
    o.resolution = 48;
    const TriMesh unmasked = marchingCubes(fit.unmaskedField(), viewBounds<3>(scene.view, fit.data.points), o);
    const TriMesh masked = marchingCubes(fit.field(), viewBounds<3>(scene.view, fit.data.points), o);
    // The mask only removes: nothing of the masked mesh lies where the field is flat.
    CHECK(masked.triangleCount() <= unmasked.triangleCount());
    int flatVertices = 0;
    for (int v = 0; v < masked.vertexCount(); ++v) {
      Vec<3> g;
      const double f = fit.unmaskedField().evaluate(masked.vertices.col(v), &g);
      flatVertices += fit.degenerateField->scale.flat(f, g.norm()) ? 1 : 0;
    }
    CHECK(flatVertices == 0);
  }
}

TEST_CASE("degenerate check: well-posed teaching scenes are not warned and not masked") {
  for (const char* name : {"wendland_sphere6_r2_none.json", "wendland_twotori_400pts_r0.6_linear.json"}) {
    CAPTURE(name);
    const SceneFit<3> fit = checkedFit(name);
    REQUIRE(fit.degenerateField);
    CHECK_FALSE(fit.degenerateField->degenerate);
    CHECK_FALSE(warnsDegenerate(fit));
    CHECK_FALSE(fit.masked);
  }
}
