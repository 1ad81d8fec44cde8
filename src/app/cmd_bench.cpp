// `hermite-lab bench [--json] [--only NAME]`: what this machine measures, median of repeats.
//   fit3d/<kernel>/N=...     3D HRBF fit on well-spread unit-sphere points (ms, assembly +
//                            factorisation + solve, as FitReport::fitMs)
//   eval3d/<kernel>          value + gradient, ns per (point, centre) pair per core
//   render/trace-baked       GPU trace of a 128³ bake at 1024×768, N = 1000 (params: bake and
//                            exact-refinement times)
//   render/field2d-refit-redraw   refit + redraw of a 200-point curve at 512×512

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench_gui.h"
#include "app/commands.h"
#include "app/output.h"
#include "core/errors.h"
#include "core/hrbf.h"
#include "core/presets.h"
#include "core/threading.h"
#include "render/field2d_view.h"
#include "render/implicit_tracer.h"

namespace hermite::app {

namespace {

using json = nlohmann::json;

struct Result {
  std::string name;
  json params;
  double median;
  std::string unit;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double nowMs() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct FitCase {
  std::string label;
  HrbfOptions options;
};

std::vector<FitCase> fitCases() {
  return {{"cubic-linear", {{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0}},
          {"gaussian-r0.5", {{KernelType::Gaussian, 0.5}, Polynomial::None, 0.0}}};
}

Result benchFit(const FitCase& c, int N, int repeats) {
  const HermiteSamples<3> s = makePreset3d("sphere", N);
  std::vector<double> times;
  std::string solver;
  for (int r = 0; r < repeats; ++r) {
    FitReport rep;
    fitHrbf<3>(s, c.options, &rep);
    times.push_back(rep.fitMs);
    solver = rep.solver;
  }
  return {"fit3d/" + c.label + "/N=" + std::to_string(N),
          {{"N", N}, {"kernel", std::string(kernelName(c.options.kernel.type))},
           {"radius", c.options.kernel.radius}, {"polynomial", std::string(polynomialName(c.options.polynomial))},
           {"solver", solver}, {"repeats", repeats}},
          median(times), "ms"};
}

Result benchEval(const FitCase& c, int centres, int points, int repeats) {
  const HermiteSamples<3> s = makePreset3d("sphere", centres);
  const HrbfModel<3> model = fitHrbf<3>(s, c.options);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  Points<3> X(3, points);
  for (int i = 0; i < points; ++i) X.col(i) = Vec<3>(u(rng), u(rng), u(rng));
  Eigen::VectorXd f;
  Points<3> G;
  model.evaluateBatch(X, f, &G);  // warm-up
  std::vector<double> perPair;
  const int threads = threadCount();
  for (int r = 0; r < repeats; ++r) {
    const double t0 = nowMs();
    model.evaluateBatch(X, f, &G);
    const double ms = nowMs() - t0;
    perPair.push_back(ms * 1e6 * threads / (double(points) * centres));
  }
  return {"eval3d/" + c.label,
          {{"centres", centres}, {"points", points}, {"threads", threads}, {"what", "value+gradient"},
           {"repeats", repeats}},
          median(perPair), "ns/pair/core"};
}

}  // namespace

int runBench(const BenchArgs& args) {
  std::vector<std::pair<std::string, std::function<Result()>>> jobs;
  const int fitRepeats = args.quick ? 1 : 7;
  for (const FitCase& c : fitCases()) {
    for (int N : {100, 250, 500, 1000}) {
      const int repeats = args.quick ? 1 : (N >= 1000 ? 5 : fitRepeats);
      jobs.emplace_back("fit3d/" + c.label + "/N=" + std::to_string(N), [c, N, repeats] { return benchFit(c, N, repeats); });
    }
  }
  for (const FitCase& c : fitCases()) {
    const int points = args.quick ? 2000 : 20000;
    const int repeats = args.quick ? 1 : 7;
    jobs.emplace_back("eval3d/" + c.label, [c, points, repeats] { return benchEval(c, 1000, points, repeats); });
  }

  // Rendering (issue 3 §6), on this machine's OpenGL (llvmpipe here) through OSMesa.
  jobs.emplace_back("render/bake-trace-refine", [quick = args.quick]() -> Result {
    const render::TracerBenchResult r =
        quick ? render::benchTracer(50, 100, 32, 128, 96, 1) : render::benchTracer(250, 1000, 128, 1024, 768, 3);
    return {"render/trace-baked", {{"bake_ms", r.bakeMs}, {"bake_resolution", r.bakeResolution},
            {"bake_centres", r.bakeCentres}, {"refine_ms", r.refineMs}, {"trace_centres", r.traceCentres},
            {"width", r.width}, {"height", r.height}, {"hit_pixels", r.hitPixels}},
            r.traceMs, "ms/frame"};
  });
  jobs.emplace_back("render/field2d-refit-redraw", [quick = args.quick]() -> Result {
    render::Field2dBenchOptions o;
    if (quick) {
      o.points = 40;
      o.size = 128;
      o.repetitions = 1;
    }
    const render::Field2dBenchResult r = render::benchField2dRefitRedraw(o);
    return {"render/field2d-refit-redraw", {{"points", o.points}, {"size", o.size}, {"fit_ms", r.fitMs},
            {"evaluate_ms", r.evaluateMs}, {"draw_ms", r.drawMs}}, r.medianMs, "ms"};
  });

  // GUI latency (issue 4 §5): dragging a sample until the refitted view is on screen.
  for (const auto& [dim, n] : {std::pair{3, 250}, std::pair{2, 200}}) {
    const std::string name = "gui/drag-latency-" + std::to_string(dim) + "d/N=" + std::to_string(n);
    jobs.emplace_back(name, [name, dim = dim, n = n, quick = args.quick]() -> Result {
      const DragLatencyResult r = benchDragLatency(dim, quick ? 40 : n, quick ? 2 : 15, quick ? 400 : 1280, quick ? 300 : 800);
      return {name, {{"samples", r.samples}, {"width", r.width}, {"height", r.height}, {"moves", r.moves},
                     {"max_ms", r.maxMs}, {"fit_ms", r.fitMs}, {"view_ms", r.viewMs}}, r.medianMs, "ms"};
    });
  }

  std::vector<Result> results;
  for (auto& [name, job] : jobs) {
    if (!args.only.empty() && name.find(args.only) == std::string::npos) continue;
    results.push_back(job());
    if (!args.json) {
      char line[256];
      std::snprintf(line, sizeof line, "%-32s %12.4g %s\n", results.back().name.c_str(), results.back().median,
                    results.back().unit.c_str());
      writeStdout(line);
      std::fflush(stdout);
    }
  }
  if (results.empty()) throw UsageError("bench --only '" + args.only + "' matches no benchmark");
  if (args.json) {
    json out;
    out["cores"] = availableCores();
    out["threads"] = threadCount();
    json arr = json::array();
    for (const Result& r : results)
      arr.push_back({{"name", r.name}, {"params", r.params}, {"median", r.median}, {"unit", r.unit}});
    out["results"] = std::move(arr);
    writeStdout(out.dump(2) + "\n");
  } else {
    writeStdout("cores " + std::to_string(availableCores()) + ", threads " + std::to_string(threadCount()) + "\n");
  }
  return 0;
}

}  // namespace hermite::app
