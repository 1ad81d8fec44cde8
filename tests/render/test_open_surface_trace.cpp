// The GPU tracer on an open surface (docs/maths.md, "No data"): a global fit of a spherical cap's
// samples with their data reach (ReachMaskedField) is seen from below, through the cap's opening.
// The interpolant closes the cap into a ball in front of it, where it has no data: the baked
// march passes that zero and shows the cap's inside, as the CPU tracer and the mesh do, where it
// used to stop there and show the background.

#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "core/pu/pu_model.h"
#include "core/pu/reach_masked_field.h"
#include "core/rbf/hrbf.h"
#include "core/trace/cpu_tracer.h"
#include "render/implicit_tracer.h"
#include "support/render_test_support.h"
#include "support/test_data.h"

using namespace hermite;
using namespace hermite::render;

namespace {

// The samples of a unit sphere's cap z ≥ 0.3, their global cubic fit and its data reach.
struct CapFit {
  HermiteSamples<3> cap;
  HrbfModel<3> global;
  std::unique_ptr<ReachMaskedField<3>> field;
  Box<3> bounds{Vec<3>::Constant(-1.5), Vec<3>::Constant(1.5)};

  CapFit() {
    const HermiteSamples<3> sphere = hermite::testing::goldenSphere(1200);
    std::vector<int> keep;
    for (int i = 0; i < sphere.size(); ++i)
      if (sphere.points(2, i) >= 0.3) keep.push_back(i);
    cap.points = sphere.points(Eigen::all, keep);
    cap.normals = sphere.normals(Eigen::all, keep);
    global = fitHrbf<3>(cap, HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0});
    field = std::make_unique<ReachMaskedField<3>>(global, cap.points, PuOptions{}.dataReach, PuOptions{}.vertexReach);
  }
  // The masked fit and its samples to the tracer, baked at 96³ over `bounds`.
  void upload(ImplicitTracer& tracer) const {
    TracerUploadOptions options;
    options.bakeResolution = 96;
    tracer.upload(*field, bounds, &cap, options);
  }
};

}  // namespace

TEST_CASE("open surface trace: a cap seen through its opening shows its inside, beyond the no-data closure") {
  const CapFit fit;
  const ReachMaskedField<3>& field = *fit.field;
  REQUIRE_FALSE(field.valid(Vec<3>(0, 0, -1)));  // the closure's far pole has no data

  auto context = hermite::render::testing::makeTestContext();
  ImplicitTracer tracer;
  fit.upload(tracer);
  CameraSpec spec;
  spec.eye = {0.0, 0.0, -4.0};  // below: the opening faces the eye
  spec.up = {0.0, 1.0, 0.0};
  const int W = 64, H = 64;
  const Camera camera(spec, Projection::Perspective, W, H, 1.0);
  const TraceResult result = tracer.render(camera, TraceSettings{});
  int hits = 0, inside = 0, onCap = 0, closure = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t p = std::size_t(j) * W + i;
      if (!result.hit[p]) continue;
      ++hits;
      const Ray ray = camera.pixelRay(i, j);
      const Vec<3> x = ray.origin + double(result.depth[p]) * ray.direction;
      const Vec<3> n(result.normal[3 * p], result.normal[3 * p + 1], result.normal[3 * p + 2]);
      inside += n.dot(ray.direction) > 0 ? 1 : 0;  // seen from inside
      onCap += std::abs(x.norm() - 1.0) <= 0.05 && x.z() >= 0.3 ? 1 : 0;
      closure += x.z() < -0.2 ? 1 : 0;  // the interpolant's closure, far below the samples
    }
  CAPTURE(hits);
  CAPTURE(inside);
  CAPTURE(onCap);
  CAPTURE(closure);
  // The opening (z = 0.3, radius 0.95) seen from 4.3 away: a disc of about 19 pixels' radius.
  CHECK(hits > 900);
  CHECK(inside >= 0.95 * hits);
  CHECK(onCap >= 0.6 * hits);  // the rest: the zero set's run past the rim, within reach, seen around the opening
  CHECK(closure == 0);
}

TEST_CASE("open surface trace: the rim of an open cap has no gaps where the bake passes a zero the field rejects") {
  // Seen obliquely from below, rays near the cap's rim meet the interpolant's zero in front of it
  // where the bake's filtered marks still say "data" but the true field says none. Refinement
  // used to turn such a hit into a miss: a ring of background pixels between the cap's outside
  // and the inside seen through its opening. Now it follows the ray on through the bake.
  const CapFit fit;
  const ReachMaskedField<3>& field = *fit.field;
  auto context = hermite::render::testing::makeTestContext();
  ImplicitTracer tracer;
  fit.upload(tracer);
  CameraSpec spec;
  spec.eye = {0.0, -2.6, -3.0};
  spec.up = {0.0, 0.0, 1.0};
  const int W = 192, H = 192;
  const Camera camera(spec, Projection::Perspective, W, H, 1.0);
  const TraceResult result = tracer.render(camera, TraceSettings{});
  // Misses next to a hit, traced by the CPU reference tracer (which passes zeros without data).
  const CpuTracer cpu(field, fit.bounds);
  int hits = 0, edge = 0, lost = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t p = std::size_t(j) * W + i;
      if (result.hit[p]) {
        ++hits;
        continue;
      }
      bool nextToHit = false;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii >= 0 && jj >= 0 && ii < W && jj < H) nextToHit = nextToHit || result.hit[std::size_t(jj) * W + ii];
        }
      if (!nextToHit) continue;
      ++edge;
      lost += cpu.trace(camera.pixelRay(i, j)).hit ? 1 : 0;
    }
  CAPTURE(hits);
  CAPTURE(edge);
  CAPTURE(lost);
  CHECK(hits > 10000);
  // Before the refinement followed rejected hits on, 5 of these pixels were lost here; one pixel
  // of slack for a grazing silhouette, where the two tracers' ε differ.
  CHECK(lost <= 1);
}
