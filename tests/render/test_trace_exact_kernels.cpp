#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/cpu_tracer.h"
#include "core/hrbf.h"
#include "core/presets.h"
#include "core/view_bounds.h"
#include "render/implicit_tracer.h"
#include "render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

// Silhouette IoU and median normal angle (degrees) of an exact-shader render against the CPU
// reference tracer, same camera and bounds.
void checkExactMode(const RadialSum<3>& model, const Box<3>& bounds) {
  auto context = testing::makeTestContext();
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 32;
  tracer.upload(model, bounds, nullptr, upload);
  REQUIRE(tracer.hasExactModel());
  TraceSettings settings;
  settings.mode = TracerMode::Exact;
  settings.refineExact = false;
  CameraSpec spec;
  spec.eye = {1.8, 2.2, 2.6};
  const Camera camera(spec, Projection::Perspective, 64, 64, 1.5);
  const CpuTraceResult reference = traceImage(model, camera, bounds, settings.background);
  const TraceResult result = tracer.render(camera, settings);
  std::vector<double> angles;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const std::size_t p = std::size_t(j) * 64 + i;
      if (result.hit[p] && reference.hit[p])
        angles.push_back(std::acos(std::clamp(result.normalAt(i, j).dot(reference.normalAt(i, j)), -1.0, 1.0)) * 180 / M_PI);
    }
  REQUIRE(angles.size() > 100);
  std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
  CHECK(maskIoU(result.hit, reference.hit) >= 0.99);
  CHECK(angles[angles.size() / 2] <= 2.0);
}

}  // namespace

// Known bug (not covered here, see the issue notes): exact mode draws false surfaces for the
// RBF-offset models and the polyharmonic HRBF — the GPU reports hits where the CPU evaluation of
// the same coefficients gives f ≈ 0.6–0.8 — in float and in double alike, so it is not precision.
TEST_CASE("exact shader mode matches the CPU reference for the HRBF kernels") {
  const HermiteSamples<3> s = makePreset3d("torus", 60);
  const Box<3> bounds = defaultViewBounds<3>(s.points);
  struct Case {
    Kernel kernel;
    Polynomial poly;
  };
  for (const Case& c : {Case{{KernelType::Gaussian, 0.45}, Polynomial::None},
                        Case{{KernelType::Wendland, 1.2}, Polynomial::Linear},
                        Case{{KernelType::Multiquadric, 0.5}, Polynomial::Linear},
                        Case{{KernelType::InverseMultiquadric, 0.5}, Polynomial::Quadratic},
                        Case{{KernelType::Cubic, 1.0}, Polynomial::Quadratic}}) {
    CAPTURE(kernelName(c.kernel.type));
    CAPTURE(polynomialName(c.poly));
    FitReport rep;
    const HrbfModel<3> m = fitHrbf<3>(s, {c.kernel, c.poly, 0.0}, &rep);
    CAPTURE(rep.conditionEstimate);
    checkExactMode(m, bounds);
  }
}
