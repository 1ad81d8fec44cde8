// `hermite-lab bench [--json] [--only NAME]`: what this machine measures, median of repeats.
//   fit3d/<kernel>/N=...     3D HRBF fit on well-spread unit-sphere points (ms, assembly +
//                            factorisation + solve, as FitReport::fitMs)
//   eval3d/<kernel>          value + gradient, ns per (point, centre) pair per core
//   render/trace-baked       GPU trace of a 128³ bake at 1024×768, N = 1000 (params: bake and
//                            exact-refinement times)
//   render/field2d-refit-redraw   refit + redraw of a 200-point curve at 512×512
//   io/ply-load/N=1000000    read + parse a binary PLY of N oriented points (loadMeshFile, ms;
//                            params: the whole point loader with validateSamples, file size)

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/output.h"
#include "core/errors.h"
#include "core/hrbf.h"
#include "core/io_points.h"
#include "core/mesh_io.h"
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

// N oriented points, jittered about the unit sphere, written once as binary PLY (floats).
Result benchPlyLoad(int N, int repeats) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  TriMesh cloud;
  cloud.vertices.resize(3, N);
  cloud.normals.resize(3, N);
  for (int i = 0; i < N; ++i) {
    const Vec<3> n = Vec<3>(gauss(rng), gauss(rng), gauss(rng)).normalized();
    cloud.normals.col(i) = n;
    cloud.vertices.col(i) = n * (1 + 0.01 * gauss(rng));
  }
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("hermite_bench_points_" + std::to_string(::getpid()) + ".ply")).string();
  saveMesh(path, cloud);
  std::vector<double> meshMs, samplesMs;
  std::vector<std::string> warnings;
  try {
    for (int r = 0; r < repeats; ++r) {
      double t0 = nowMs();
      const TriMesh m = loadMeshFile(path);
      meshMs.push_back(nowMs() - t0);
      if (m.vertexCount() != N) throw NumericalError("bench io/ply-load: read back " + std::to_string(m.vertexCount()) + " points");
      t0 = nowMs();
      const HermiteSamples<3> s = loadPointFile3d(path, warnings);
      samplesMs.push_back(nowMs() - t0);
    }
  } catch (...) {
    std::filesystem::remove(path);
    throw;
  }
  const auto bytes = std::filesystem::file_size(path);
  std::filesystem::remove(path);
  return {"io/ply-load/N=" + std::to_string(N),
          {{"N", N}, {"bytes", bytes}, {"point_loader_ms", median(samplesMs)}, {"repeats", repeats},
           {"what", "binary little-endian PLY, float x y z nx ny nz"}},
          median(meshMs), "ms"};
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

  jobs.emplace_back("io/ply-load", [quick = args.quick] {
    return quick ? benchPlyLoad(100000, 1) : benchPlyLoad(1000000, 5);
  });

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
