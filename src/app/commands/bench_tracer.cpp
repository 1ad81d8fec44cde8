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
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  HrbfOptions options;
  options.kernel = Kernel{KernelType::Cubic, 1.0};
  options.polynomial = Polynomial::Linear;

  render::ImplicitTracer tracer;
  {
    const HermiteSamples<3> samples = makePreset3d("torus", bakeCentres);
    const HrbfModel<3> model = fitHrbf(samples, options);
    const Box<3> bounds = defaultViewBounds<3>(samples.points);
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
      VolumeBakeOptions bakeOptions;
      bakeOptions.resolution = bakeResolution;
      const auto t0 = std::chrono::steady_clock::now();
      const VolumeBake bake = bakeVolume(model, bounds, bakeOptions);
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    out.bakeMs = median(times);
  }
  const HermiteSamples<3> samples = makePreset3d("torus", traceCentres);
  const HrbfModel<3> model = fitHrbf(samples, options);
  const Box<3> bounds = defaultViewBounds<3>(samples.points);
  render::TracerUploadOptions upload;
  upload.bakeResolution = bakeResolution;
  tracer.upload(model, bounds, &samples, upload);
  CameraSpec spec;
  spec.eye = {1.6, -2.4, 1.8};
  const Camera camera(spec, Projection::Perspective, width, height, 1.5);
  render::TraceSettings settings;
  std::vector<double> trace, refine;
  // Traces back to back, as while orbiting a settled model; then the refinements, whose CPU
  // threads would slow a trace that follows them.
  settings.refineExact = false;
  for (int r = 0; r < 2 * repeats + 1; ++r) {
    const render::TraceResult frame = tracer.render(camera, settings);
    trace.push_back(frame.traceMs);
    out.tracedPixels = frame.tracedPixels;
  }
  // The same frames tracing every pixel: what skipping the empty tiles saves.
  std::vector<double> traceAll;
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
  return out;
}

}  // namespace hermite::app
