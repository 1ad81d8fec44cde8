#include "app/commands/bench_tracer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/rbf/hrbf.h"
#include "core/shapes/presets.h"
#include "core/trace/default_view_bounds.h"
#include "core/trace/volume_bake.h"
#include "render/gl/context.h"
#include "render/implicit_tracer.h"

namespace hermite::app {

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

HrbfOptions cubicLinear() {
  HrbfOptions options;
  options.kernel = Kernel{KernelType::Cubic, 1.0};
  options.polynomial = Polynomial::Linear;
  return options;
}

// Median wall time of baking the HRBF of `centres` torus samples at `resolution`³ (ms).
double medianBakeMs(int centres, int resolution, int repeats) {
  const HermiteSamples<3> samples = makePreset3d("torus", centres);
  const HrbfModel<3> model = fitHrbf(samples, cubicLinear());
  const Box<3> bounds = defaultViewBounds<3>(samples.points);
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    VolumeBakeOptions bakeOptions;
    bakeOptions.resolution = resolution;
    const auto t0 = std::chrono::steady_clock::now();
    const VolumeBake bake = bakeVolume(model, bounds, bakeOptions);
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return median(times);
}

// Traces back to back, as while orbiting a settled model (then the same frames tracing every
// pixel: what skipping the empty tiles saves); then the refinements, whose CPU threads would
// slow a trace that follows them.
void timeTraces(render::ImplicitTracer& tracer, const Camera& camera, int repeats, TracerBenchResult& out) {
  render::TraceSettings settings;
  std::vector<double> trace, traceAll, refine;
  settings.refineExact = false;
  for (int r = 0; r < 2 * repeats + 1; ++r) {
    const render::TraceResult frame = tracer.render(camera, settings);
    trace.push_back(frame.traceMs);
    out.tracedPixels = frame.tracedPixels;
  }
  settings.skipEmptyTiles = false;
  for (int r = 0; r < 2 * repeats + 1; ++r) traceAll.push_back(tracer.render(camera, settings).traceMs);
  settings.skipEmptyTiles = true;
  for (int r = 0; r < repeats; ++r) {
    settings.refineExact = true;
    const render::TraceResult refined = tracer.render(camera, settings);
    refine.push_back(refined.refineMs);
    out.hitPixels = refined.refinedPixels;
  }
  out.traceMs = median(trace);
  out.traceAllPixelsMs = median(traceAll);
  out.refineMs = median(refine);
}

}  // namespace

TracerBenchResult benchTracer(int bakeCentres, int traceCentres, int bakeResolution, int width, int height,
                              int repeats, const char* backend) {
  TracerBenchResult out;
  out.bakeCentres = bakeCentres;
  out.traceCentres = traceCentres;
  out.bakeResolution = bakeResolution;
  out.width = width;
  out.height = height;
  repeats = std::max(1, repeats);
  render::ContextOptions contextOptions;
  contextOptions.width = width;
  contextOptions.height = height;
  auto context = render::createContext(backend, contextOptions);
  render::ImplicitTracer tracer;
  out.bakeMs = medianBakeMs(bakeCentres, bakeResolution, repeats);
  const HermiteSamples<3> samples = makePreset3d("torus", traceCentres);
  const HrbfModel<3> model = fitHrbf(samples, cubicLinear());
  const Box<3> bounds = defaultViewBounds<3>(samples.points);
  render::TracerUploadOptions upload;
  upload.bakeResolution = bakeResolution;
  tracer.upload(model, bounds, &samples, upload);
  CameraSpec spec;
  spec.eye = {1.6, -2.4, 1.8};
  const Camera camera(spec, Projection::Perspective, width, height, 1.5);
  timeTraces(tracer, camera, repeats, out);
  return out;
}

}  // namespace hermite::app
