// The GPU tracer on a degenerate field (docs/maths.md, "Degenerate fields"): its flat regions are
// no data, so the march passes the zeros it meets there and the refinement takes no root there —
// no speckled box where f = 0 beyond r of every sample. Scene: wendland_sphere6_r1_none, whose zero
// set is six discs of radius ≈ 1 on the faces of the cube [−1, 1]³ and whose f is exactly 0
// wherever no sample is within r = 1 (the bounds' corners and faces at 1.25).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/implicit_tracer.h"
#include "scene/degenerate_check.h"
#include "scene/scene_file.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

struct DiscCounts {
  int hits = 0;
  int offCube = 0;      // hit points farther than `tolerance` outside the cube [−1, 1]³
  int outsideDisc = 0;  // hit pixels whose ray passes beyond the front disc's rim (head-on view)
  double offFaces = 0;  // the largest distance of a hit point from the cube's face planes
};

// Hits of `result` classified by where their points lie; `frontRim` > 0 also counts the hit
// pixels whose ray's angle to the view axis is above atan(frontRim) (the eye on the z axis).
DiscCounts classify(const TraceResult& result, const Camera& camera, double tolerance, double frontRim) {
  DiscCounts c;
  const int W = result.image.width, H = result.image.height;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t p = std::size_t(j) * W + i;
      if (!result.hit[p]) continue;
      ++c.hits;
      const Ray ray = camera.pixelRay(i, j);
      const Vec<3> x = ray.origin + double(result.depth[p]) * ray.direction;
      if (x.cwiseAbs().maxCoeff() > 1.0 + tolerance) ++c.offCube;
      c.offFaces = std::max(c.offFaces, std::abs(x.cwiseAbs().maxCoeff() - 1.0));
      const Vec<3> d = ray.direction.normalized();
      if (frontRim > 0 && std::hypot(d.x(), d.y()) / std::abs(d.z()) > frontRim) ++c.outsideDisc;
    }
  return c;
}

}  // namespace

TEST_CASE("flat-masked trace: a degenerate field draws its discs and no speckle where f = 0") {
  const Scene scene = loadSceneFile(std::string(HERMITE_SOURCE_DIR) + "/assets/scenes/wendland_sphere6_r1_none.json");
  SceneFit<3> fit = fitScene<3>(scene);
  checkDegenerateField<3>(scene, fit);  // as the window's fit worker does
  REQUIRE(fit.masked);  // the degenerate check marked the flat regions
  const Box<3> bounds = viewBounds<3>(scene.view, fit.data.points);
  REQUIRE(bounds.hi.x() > 1.2);  // the bounds' faces lie in the flat region, beyond every disc

  auto context = testing::makeTestContext();
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 64;
  tracer.upload(fit.field(), bounds, &fit.data, upload);
  const double cell = bounds.extent().x() / (upload.bakeResolution - 1);
  TraceSettings settings;  // baked, refined against the true field

  SUBCASE("head-on: the front disc fills its rim, and every hit lies on a disc") {
    CameraSpec spec;  // the scene's camera: eye (0, 0, 4), fov 40°
    const Camera camera(spec, Projection::Perspective, 96, 96, 1.0);
    const DiscCounts c = classify(tracer.render(camera, settings), camera, cell, 1.0 / 3.0 + 0.02);
    // The disc z = 1 of radius 1 seen from 3 away: tan = 1/3, 0.916 of the half-height of 96 px.
    const double discPixels = M_PI * std::pow(0.916 * 48, 2);
    CAPTURE(c.hits);
    CAPTURE(discPixels);
    CHECK(c.hits >= 0.9 * discPixels);
    CHECK(c.offCube == 0);
    CAPTURE(c.outsideDisc);
    // Beyond the front disc's rim the rays pass the flat region's zeros (no data) and meet the
    // four side discs from inside (about 4 % of the hits): surface, on the cube's faces like every
    // hit; speckle would lie inside the flat box.
    CHECK(c.offFaces < 1e-3 * cell);
    CHECK(c.outsideDisc <= 0.05 * c.hits);
  }
  SUBCASE("oblique: three discs, no hit on the flat box around them") {
    CameraSpec spec;
    spec.eye = {2.5, 2.0, 3.0};
    const Camera camera(spec, Projection::Perspective, 96, 72, 1.0);
    const DiscCounts c = classify(tracer.render(camera, settings), camera, cell, 0);
    CAPTURE(c.hits);
    CHECK(c.hits >= 0.15 * 96 * 72);
    // Before the flat mask reached the bake, about half the pixels hit the box's faces at 1.25.
    CHECK(c.offCube == 0);
  }
}
