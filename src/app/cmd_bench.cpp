// `hermite-lab bench [--json] [--only NAME]`: what this machine measures, median of repeats.
//   fit3d/<kernel>/N=...     3D HRBF fit on well-spread unit-sphere points (ms, assembly +
//                            factorisation + solve, as FitReport::fitMs)
//   eval3d/<kernel>          value + gradient, ns per (point, centre) pair per core
//   render/trace-baked       GPU trace of a 128³ bake at 1024×768, N = 1000 (params: bake and
//                            exact-refinement times)
//   render/field2d-refit-redraw   refit + redraw of a 200-point curve at 512×512
//   pu3d/two-tori/N=...      partition-of-unity fit (cubic, linear, ≤ 20 per box, overlap 1.5)
//                            of N random area-uniform points on two interlinked tori with exact
//                            normals (s); params: peak memory, evaluation throughput, and the
//                            zero set's distance |f|/‖∇f‖ at fresh exact surface points

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <random>

#include <sys/resource.h>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/output.h"
#include "core/errors.h"
#include "core/hrbf.h"
#include "core/presets.h"
#include "core/pu_model.h"
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

// N area-uniform random points on the two-tori preset's exact tori (rejection on the tube
// angle: the area element is ∝ R + r cos v), with exact outward normals.
HermiteSamples<3> randomTwoTori(int N, unsigned seed) {
  const std::vector<TorusGeometry> tori = presetTori("two-tori");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), unit(0, 1);
  HermiteSamples<3> s;
  s.points.resize(3, N);
  s.normals.resize(3, N);
  for (int i = 0; i < N;) {
    const TorusGeometry& t = tori[i % tori.size()];
    const double u = angle(rng), v = angle(rng);
    if (unit(rng) * (t.major + t.minor) > t.major + t.minor * std::cos(v)) continue;
    // Orthonormal frame (e1, e2, axis).
    const Vec<3> a = t.axis.normalized();
    const Vec<3> e1 = (std::abs(a.x()) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY()).cross(a).normalized();
    const Vec<3> e2 = a.cross(e1);
    const Vec<3> radial = std::cos(u) * e1 + std::sin(u) * e2;
    const Vec<3> n = std::cos(v) * radial + std::sin(v) * a;
    s.points.col(i) = t.centre + t.major * radial + t.minor * n;
    s.normals.col(i) = n;
    ++i;
  }
  return s;
}

double peakRssMb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return double(r.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

Result benchPuTori(int N, const std::string& label) {
  const double g0 = nowMs();
  const HermiteSamples<3> s = randomTwoTori(N, 1);
  const double generateMs = nowMs() - g0;
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.maxPointsPerBox = 20;
  o.overlap = 1.5;
  PuReport rep;
  const double t0 = nowMs();
  const PuModel<3> pu = fitPu<3>(s, o, &rep);
  const double fitS = (nowMs() - t0) / 1000.0;
  const double rssAfterFit = peakRssMb();
  // Throughput: value + gradient at random points of the bounding box.
  const Box<3> box = boundingBox<3>(s.points);
  const int evalPoints = 200000;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  Points<3> X(3, evalPoints);
  for (int i = 0; i < evalPoints; ++i)
    for (int k = 0; k < 3; ++k) X(k, i) = box.lo(k) + u(rng) * (box.hi(k) - box.lo(k));
  Eigen::VectorXd f;
  Points<3> G;
  const double e0 = nowMs();
  pu.evaluateBatch(X, f, &G);
  const double evalMs = nowMs() - e0;
  // Accuracy at fresh exact surface points: |f|/‖∇f‖ (the first-order distance to the zero set).
  const HermiteSamples<3> fresh = randomTwoTori(20000, 2);
  pu.evaluateBatch(fresh.points, f, &G);
  const double diagonal = box.extent().norm();
  double maxD = 0, sumD = 0, maxAngle = 0;
  for (int i = 0; i < fresh.size(); ++i) {
    const double d = std::abs(f(i)) / std::max(G.col(i).norm(), 1e-300);
    maxD = std::max(maxD, d);
    sumD += d;
    maxAngle = std::max(maxAngle, std::acos(std::clamp(G.col(i).normalized().dot(fresh.normals.col(i)), -1.0, 1.0)));
  }
  return {"pu3d/two-tori/N=" + label,
          {{"N", N}, {"kernel", "cubic"}, {"polynomial", "linear"}, {"max_points_per_box", o.maxPointsPerBox},
           {"overlap", o.overlap}, {"boxes", rep.boxes}, {"max_support_samples", rep.maxSupportSamples},
           {"mean_support_samples", rep.meanSupportSamples},
           {"grown_supports", rep.grownSupports}, {"tree_ms", rep.treeMs}, {"generate_ms", generateMs},
           {"peak_rss_mb", rssAfterFit}, {"eval_points_per_s", evalPoints / (evalMs / 1000.0)},
           {"eval_what", "value+gradient, random points in the bounding box"},
           {"held_out", fresh.size()}, {"max_distance_rel_diag", maxD / diagonal},
           {"mean_distance_rel_diag", sumD / fresh.size() / diagonal},
           {"max_normal_angle_deg", maxAngle * 180.0 / M_PI}, {"threads", threadCount()}},
          fitS, "s"};
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

  // Partition of unity at scale (issue 6 §3): run on their own (--only pu3d), they take a while.
  for (const auto& [label, N] : {std::pair<const char*, int>{"1e5", 100000}, {"1e6", 1000000}}) {
    const int n = args.quick ? N / 100 : N;
    jobs.emplace_back(std::string("pu3d/two-tori/N=") + label, [n, label = std::string(label)] { return benchPuTori(n, label); });
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
