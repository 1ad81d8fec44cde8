#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rbf/hrbf.h"
#include "core/rbf/rbf_offset.h"
#include "core/shapes/presets.h"
#include "core/trace/cpu_tracer.h"
#include "core/trace/default_view_bounds.h"
#include "render/implicit_tracer.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

// Silhouette IoU and median normal angle (degrees) of an exact-shader render against the CPU
// reference tracer, same camera and bounds.
// minStepCells: the march's ε in 1e-3·diagonal units, for both tracers.
TraceResult checkExactMode(const RadialSum<3>& model, const Box<3>& bounds,
                           ExactPrecision precision = ExactPrecision::Auto, double minStepCells = 0.1) {
  auto context = testing::makeTestContext();
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 32;
  tracer.upload(model, bounds, nullptr, upload);
  REQUIRE(tracer.hasExactModel());
  TraceSettings settings;
  settings.mode = TracerMode::Exact;
  settings.refineExact = false;
  settings.exactPrecision = precision;
  settings.minStepCells = minStepCells;
  CpuTraceOptions cpuOptions;
  cpuOptions.minStep = minStepCells * 1e-3;
  CameraSpec spec;
  spec.eye = {1.8, 2.2, 2.6};
  const Camera camera(spec, Projection::Perspective, 64, 64, 1.5);
  const CpuTraceResult reference = traceImage(model, camera, bounds, settings.background, cpuOptions);
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
  return result;
}

}  // namespace

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
                        Case{{KernelType::Cubic, 1.0}, Polynomial::Quadratic},
                        Case{{KernelType::Polyharmonic, 1.0}, Polynomial::Quadratic}}) {
    CAPTURE(kernelName(c.kernel.type));
    CAPTURE(polynomialName(c.poly));
    FitReport rep;
    const HrbfModel<3> m = fitHrbf<3>(s, {c.kernel, c.poly, 0.0}, &rep);
    CAPTURE(rep.conditionEstimate);
    checkExactMode(m, bounds);
  }
}

// RBF-offset models are dipole pairs δ = 0.01 apart whose terms cancel by 5–6 orders of magnitude:
// the tracer sums them in double (float drew false surfaces). Their Lipschitz bounds are loose, so
// the march takes ε steps; with the default ε most rays outrun the shader's loop budget on llvmpipe
// and go to the CPU (correct, slow), so this test takes ε = 5e-3 of the diagonal for both tracers
// and checks the shader's own double sums. (Both used to go wrong silently: Mesa's software
// rasteriser ends all loops of a shader invocation after 65 535 iterations in all.)
TEST_CASE("exact shader mode matches the CPU reference for RBF-offset models") {
  const HermiteSamples<3> s = makePreset3d("torus", 40);
  const Box<3> bounds = defaultViewBounds<3>(s.points);
  for (const KernelType kernel : {KernelType::Gaussian, KernelType::Cubic, KernelType::Polyharmonic}) {
    CAPTURE(kernelName(kernel));
    RbfOffsetOptions options;
    options.kernel = {kernel, 0.5};
    options.polynomial = kernel == KernelType::Gaussian ? Polynomial::None : Polynomial::Quadratic;
    const RbfOffsetModel<3> m = fitRbfOffset<3>(s, options);
    const TraceResult result = checkExactMode(m, bounds, ExactPrecision::Auto, 5.0);
    CHECK(result.cpuTracedPixels < 64 * 64 / 4);  // mostly the shader's own work
    if (kernel != KernelType::Gaussian) CHECK(result.exactDouble);  // Σ|terms| ≈ 1e5–1e6 against f ≈ 1
  }
}

TEST_CASE("exact shader mode: float and double sums agree where float suffices") {
  const HermiteSamples<3> s = makePreset3d("torus", 60);
  const Box<3> bounds = defaultViewBounds<3>(s.points);
  const HrbfModel<3> gaussian = fitHrbf<3>(s, {{KernelType::Gaussian, 0.45}, Polynomial::None, 0.0});
  const TraceResult inFloat = checkExactMode(gaussian, bounds, ExactPrecision::Float);
  const TraceResult inDouble = checkExactMode(gaussian, bounds, ExactPrecision::Double);
  CHECK_FALSE(inFloat.exactDouble);
  CHECK(inDouble.exactDouble);
  CHECK(maskIoU(inFloat.hit, inDouble.hit) >= 0.99);
}
