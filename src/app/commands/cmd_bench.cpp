// `hermite-lab bench [--json] [--only NAME]`: what this machine measures, median of repeats.
//   fit3d/<kernel>/N=...     3D HRBF fit on well-spread unit-sphere points (ms, assembly +
//                            factorisation + solve, as FitReport::fitMs)
//   eval3d/<kernel>          value + gradient, ns per (point, centre) pair per core
//   render/trace-baked       GPU trace of a 128³ bake at 1024×768, N = 1000 (params: bake and
//                            exact-refinement times, traced_pixels: those not in tiles proven
//                            empty, trace_all_pixels_ms: the same frame tracing every pixel)
//   render/field2d-refit-redraw   refit + redraw of a 200-point curve at 512×512
//   io/ply-load/N=1000000    read + parse a binary PLY of N oriented points (loadMeshFile, ms;
//                            params: the whole point loader with validateSamples, file size)
//   mesh/marching-cubes/...  marching cubes of an N = 1000 HRBF (unit sphere preset) over
//                            [-1.25, 1.25]³ (ms; params: field-evaluation ms, triangles)
//   holefill/100k-10holes    fillHoles on a ≈100k-triangle torus with 10 holes of ≈50 boundary
//                            edges each (ms, whole pipeline; params: holes, edges, |f|)
//   holefill/100k-100holes   the same with 100 holes of about 10–60 boundary edges (params also:
//                            progress_gap_ms, the longest time between two progress calls)
//   holefill/2000-edge-hole  one 2 000-edge non-planar hole in a wavy open sphere (as above)

//   pu3d/two-tori/N=...      partition-of-unity fit (cubic, linear, ≤ 20 per box, overlap 1.5)
//                            of N random area-uniform points on two interlinked tori with exact
//                            normals (s); params: peak memory, evaluation throughput, and the
//                            zero set's distance |f|/‖∇f‖ at fresh exact surface points

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands/bench_field2d.h"
#include "app/commands/bench_gui.h"
#include "app/commands/bench_lapack.h"
#include "app/commands/bench_tracer.h"
#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "core/base/blas_setup.h"
#include "core/base/errors.h"
#include "core/base/threading.h"
#include "core/mesh/hole_fill.h"
#include "core/mesh/marching_cubes.h"
#include "core/pu/pu_model.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/mesh_shapes.h"
#include "core/shapes/presets.h"
#include "io/mesh_file.h"
#include "io/point_file.h"
#include "render/field2d_view.h"
#include "scene/patch_document.h"

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
          {"cubic-none", {{KernelType::Cubic, 1.0}, Polynomial::None, 0.0}},
          {"gaussian-r0.5", {{KernelType::Gaussian, 0.5}, Polynomial::None, 0.0}}};
}

Result benchFit(const FitCase& c, int N, int repeats) {
  const HermiteSamples<3> s = makePreset3d("sphere", N);
  std::vector<double> times, factorMs, gflops;
  std::map<std::string, std::vector<double>> phases;  // solve phase → its time in each repeat, ms
  std::string solver;
  double flops = 0;  // of the factorisation: the same in every repeat
  for (int r = 0; r < repeats; ++r) {
    FitReport rep;
    fitHrbf<3>(s, c.options, &rep);
    times.push_back(rep.fitMs);
    factorMs.push_back(rep.factorMs);
    gflops.push_back(rep.factorGflops);
    std::map<std::string, double> repeatPhases{{"assembly", rep.assemblyMs}};
    for (const auto& [phase, ms] : rep.solvePhasesMs) repeatPhases[phase] += ms;
    for (const auto& [phase, ms] : repeatPhases) phases[phase].push_back(ms);
    solver = rep.solver;
    flops = rep.factorGflops * rep.factorMs * 1e6;
  }
  // The factorisation against a plain dpotrf / dgetrf of the block it factorised.
  const SolverChoice path = parseSolverChoice(solver);
  const double factorGflops = median(gflops);
  const Eigen::Index k = factorisedSize(path, flops);
  const double lapackGflops = plainLapackGflops(path, k, std::min(repeats, 3));
  json phaseMedians = json::object();
  for (auto& [phase, ms] : phases) phaseMedians[phase] = median(ms);
  return {"fit3d/" + c.label + "/N=" + std::to_string(N),
          {{"N", N}, {"kernel", std::string(kernelName(c.options.kernel.type))},
           {"radius", c.options.kernel.radius}, {"polynomial", std::string(polynomialName(c.options.polynomial))},
           {"solver", solver}, {"repeats", repeats}, {"factor_ms", median(factorMs)},
           {"factor_gflops", factorGflops}, {"factorised_size", k}, {"lapack_gflops", lapackGflops},
           {"phases_ms", phaseMedians}},
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

Result benchMarchingCubes(int centres, int resolution, int repeats) {
  const HrbfModel<3> model = fitHrbf<3>(makePreset3d("sphere", centres), HrbfOptions{});
  Box<3> box;
  box.lo = Vec<3>::Constant(-1.25);
  box.hi = Vec<3>::Constant(1.25);
  std::vector<double> total, evaluate;
  int triangles = 0;
  long long evaluated = 0, points = 0;
  for (int r = 0; r < repeats; ++r) {
    MarchingReport rep;
    const TriMesh mesh = marchingCubes(model, box, {resolution}, &rep);
    total.push_back(rep.totalMs);
    evaluate.push_back(rep.evaluateMs);
    triangles = mesh.triangleCount();
    evaluated = rep.evaluatedPoints;
    points = rep.gridPoints;
  }
  return {"mesh/marching-cubes/hrbf-N=" + std::to_string(centres) + "/res=" + std::to_string(resolution),
          {{"centres", centres}, {"resolution", resolution}, {"evaluate_ms", median(evaluate)},
           {"triangles", triangles}, {"grid_points", points}, {"evaluated_points", evaluated},
           {"threads", threadCount()}, {"repeats", repeats}},
          median(total), "ms"};
}

Result benchHoleFill(bool quick, int repeats) {
  const int nu = quick ? 100 : 316, nv = quick ? 50 : 158;  // 2·nu·nv ≈ 100k triangles
  // Ten balls centred on the surface, spread over u and v; radius for ≈ 50 boundary edges.
  const double radius = quick ? 0.2 : 0.085;
  TriMesh holed = parametricTorusMesh(nu, nv, 0.7, 0.3);
  for (int h = 0; h < 10; ++h) {
    const double u = 2 * M_PI * h / 10, v = 2 * M_PI * ((3 * h) % 10) / 10;
    holed = cutBall(holed, Vec<3>((0.7 + 0.3 * std::cos(v)) * std::cos(u), (0.7 + 0.3 * std::cos(v)) * std::sin(u), 0.3 * std::sin(v)),
                    radius);
  }
  size_t edges = 0;
  const std::vector<BoundaryLoop> loops = detectHoles(holed);
  for (const BoundaryLoop& l : loops) edges += l.size();
  std::vector<double> times;
  HoleFillResult r;
  for (int i = 0; i < repeats; ++i) {
    r = fillHoles(holed);
    times.push_back(r.ms);
  }
  return {"holefill/100k-10holes",
          {{"triangles", holed.triangleCount()}, {"holes_found", r.holesFound}, {"holes_filled", r.holesFilled},
           {"mean_boundary_edges", loops.empty() ? 0.0 : double(edges) / loops.size()},
           {"triangles_added", r.trianglesAdded}, {"max_abs_f", r.maxAbsF}, {"unconverged", r.unconverged},
           {"closed", checkMesh(r.mesh).closed()}, {"repeats", repeats}},
          median(times), "ms"};
}

// fillHoles on `holed` (median of `repeats`), then once more with a progress callback: the
// longest time between two of its calls is how late a cancellation can be seen (`progress_gap_ms`).
Result benchHoleFillMesh(const std::string& name, const TriMesh& holed, int repeats) {
  const std::vector<BoundaryLoop> loops = detectHoles(holed);
  std::size_t fewest = loops.empty() ? 0 : loops[0].size(), most = 0;
  for (const BoundaryLoop& l : loops) fewest = std::min(fewest, l.size()), most = std::max(most, l.size());
  std::vector<double> times;
  HoleFillResult r;
  for (int i = 0; i < repeats; ++i) {
    r = fillHoles(holed);
    times.push_back(r.ms);
  }
  HoleFillOptions watched;
  auto last = std::chrono::steady_clock::now();
  double gapMs = 0;
  watched.progress = [&](double) {
    const auto now = std::chrono::steady_clock::now();
    gapMs = std::max(gapMs, std::chrono::duration<double, std::milli>(now - last).count());
    last = now;
    return true;
  };
  fillHoles(holed, watched);
  const MeshCheck c = checkMesh(r.mesh);
  return {name,
          {{"triangles", holed.triangleCount()}, {"holes_found", r.holesFound}, {"holes_filled", r.holesFilled},
           {"fewest_boundary_edges", fewest}, {"most_boundary_edges", most}, {"triangles_added", r.trianglesAdded},
           {"max_abs_f", r.maxAbsF}, {"unconverged", r.unconverged}, {"closed_manifold", c.closedManifold()},
           {"euler_characteristic", c.eulerCharacteristic}, {"progress_gap_ms", gapMs}, {"repeats", repeats}},
          median(times), "ms"};
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

using Jobs = std::vector<std::pair<std::string, std::function<Result()>>>;

// Patch editor: re-tessellating a 4 × 4 grid at 64 × 64 samples per patch after a
// handle moved (edit + grid + tessellation), as while dragging.
Result benchRetessellate(bool quick) {
  PatchSpec spec;
  spec.splits = {4, 4};
  spec.tessellation = 64;
  spec.knots = patchKnotData(spec);
  const int repeats = quick ? 3 : 51;
  std::vector<double> ms;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    spec = movePatchHandle(spec, PatchHandle{PatchHandle::TangentU, 2, 2, 0, 0},
                           spec.knots[2 * 5 + 2].X + Vec<3>(0.1, 0.05 * (k % 3), 0.0));
    const PatchGrid grid = buildPatchGrid(spec);
    const PatchGrid::Tessellation t = grid.tessellate(spec.tessellation);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (t.positions.cols() != 16 * 64 * 64) throw EnvironmentError("bench: unexpected tessellation size");
  }
  std::sort(ms.begin(), ms.end());
  return {"patch/retessellate-4x4-64", {{"patches", 16}, {"samples_per_patch", 64 * 64}, {"repeats", repeats}},
          ms[ms.size() / 2], "ms"};
}

// Fits and evaluation of the 3D HRBF cases.
void addFitJobs(Jobs& jobs, const BenchArgs& args) {
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
}

// Reading PLY, meshing and hole filling.
void addMeshJobs(Jobs& jobs, const BenchArgs& args) {
  jobs.emplace_back("io/ply-load", [quick = args.quick] {
    return quick ? benchPlyLoad(100000, 1) : benchPlyLoad(1000000, 5);
  });
  // Meshing and hole filling.
  for (int resolution : {64, 128}) {
    const int res = args.quick ? 16 : resolution, repeats = args.quick ? 1 : 3;
    jobs.emplace_back("mesh/marching-cubes/hrbf-N=1000/res=" + std::to_string(resolution),
                      [res, repeats, quick = args.quick] { return benchMarchingCubes(quick ? 100 : 1000, res, repeats); });
  }
  jobs.emplace_back("holefill/100k-10holes",
                    [quick = args.quick] { return benchHoleFill(quick, quick ? 1 : 5); });
  jobs.emplace_back("holefill/100k-100holes", [quick = args.quick] {
    return benchHoleFillMesh("holefill/100k-100holes",
                             quick ? holedTorusMesh(100, 50, 10, 3, 0.05, 0.15) : holedTorusMesh(316, 158, 20, 5, 0.015, 0.05),
                             quick ? 1 : 5);
  });
  jobs.emplace_back("holefill/2000-edge-hole", [quick = args.quick] {
    return benchHoleFillMesh("holefill/2000-edge-hole",
                             quick ? openWavySphereMesh(200, 20, 6, 0.3) : openWavySphereMesh(2000, 40, 13, 0.3),
                             quick ? 1 : 3);
  });
}

// Rendering, on the OpenGL that OSMesa finds on this machine.
void addTracerJobs(Jobs& jobs, const BenchArgs& args) {
  jobs.emplace_back("render/bake-trace-refine", [quick = args.quick]() -> Result {
    const TracerBenchResult r =
        quick ? benchTracer(50, 100, 32, 128, 96, 1) : benchTracer(250, 1000, 128, 1024, 768, 3);
    return {"render/trace-baked", {{"bake_ms", r.bakeMs}, {"bake_resolution", r.bakeResolution},
            {"bake_centres", r.bakeCentres}, {"refine_ms", r.refineMs}, {"trace_centres", r.traceCentres},
            {"width", r.width}, {"height", r.height}, {"hit_pixels", r.hitPixels},
            {"traced_pixels", r.tracedPixels}, {"trace_all_pixels_ms", r.traceAllPixelsMs}},
            r.traceMs, "ms/frame"};
  });
  jobs.emplace_back("render/field2d-refit-redraw", [quick = args.quick]() -> Result {
    Field2dBenchOptions o;
    if (quick) {
      o.points = 40;
      o.size = 128;
      o.repetitions = 1;
    }
    const Field2dBenchResult r = benchField2dRefitRedraw(o);
    return {"render/field2d-refit-redraw", {{"points", o.points}, {"size", o.size}, {"fit_ms", r.fitMs},
            {"evaluate_ms", r.evaluateMs}, {"draw_ms", r.drawMs}}, r.medianMs, "ms"};
  });
}

// GUI latency: dragging a sample until the refitted view is on screen.
void addDragLatencyJobs(Jobs& jobs, const BenchArgs& args) {
  for (const auto& [dim, n] : {std::pair{3, 250}, std::pair{2, 200}}) {
    const std::string name = "gui/drag-latency-" + std::to_string(dim) + "d/N=" + std::to_string(n);
    jobs.emplace_back(name, [name, dim = dim, n = n, quick = args.quick]() -> Result {
      const DragLatencyResult r = benchDragLatency(dim, quick ? 40 : n, quick ? 2 : 15, quick ? 400 : 1280, quick ? 300 : 800);
      return {name, {{"samples", r.samples}, {"width", r.width}, {"height", r.height}, {"moves", r.moves},
                     {"max_ms", r.maxMs}, {"final_ms", r.finalMs}, {"fit_ms", r.fitMs}, {"view_ms", r.viewMs}, {"frames", r.frames},
                     {"with_frame_wait_ms", r.withFrameWaitMs}}, r.medianMs, "ms"};
    });
  }
}

// A busy-frames bench's parameters; the worst frame's steps (worst_phases) say where its time went.
json busyFramesParams(const BusyFramesResult& r) {
  json phases = json::object();
  for (std::size_t k = 0; k < kFramePhaseNames.size(); ++k) phases[std::string(kFramePhaseNames[k])] = r.worstPhases.ms[k];
  phases["present"] = r.worstPresentMs;
  return json{{"samples", r.samples}, {"width", r.width}, {"height", r.height}, {"median_ms", r.medianMs},
              {"frames", r.frames}, {"total_ms", r.totalMs}, {"fit_ms", r.fitMs}, {"frames_over_33ms", r.over33},
              {"worst_phases", phases}};
}

// Frame times while a fit or a settled render runs (issue 18: ≤ 33 ms at 1280×800). The dense
// fit of 1 500 samples (6 000 unknowns) takes seconds, the 5 000-sample one (20 000 unknowns)
// many minutes.
void addBusyFramesJobs(Jobs& jobs, const BenchArgs& args) {
  for (const int n : {1500, 5000}) {
    const std::string name = "gui/frames-during-dense-fit/N=" + std::to_string(n);
    jobs.emplace_back(name, [quick = args.quick, n, name]() -> Result {
      const BusyFramesResult r = benchFramesDuringDenseFit(quick ? 300 : n, quick ? 400 : 1280, quick ? 300 : 800);
      return {name, busyFramesParams(r), r.worstMs, "ms worst frame"};
    });
  }
  jobs.emplace_back("gui/frames-during-settled-render/pu-N=5000", [quick = args.quick]() -> Result {
    const BusyFramesResult r = benchFramesDuringSettledRender(quick ? 300 : 5000, quick ? 400 : 1280, quick ? 300 : 800);
    return {"gui/frames-during-settled-render/pu-N=5000", busyFramesParams(r), r.worstMs, "ms worst frame"};
  });
}

// Rendering (on the OpenGL that OSMesa finds), the patch editor, GUI latency, PU at scale.
void addRenderJobs(Jobs& jobs, const BenchArgs& args) {
  addTracerJobs(jobs, args);
  jobs.emplace_back("patch/retessellate-4x4-64", [quick = args.quick] { return benchRetessellate(quick); });
  addDragLatencyJobs(jobs, args);
  addBusyFramesJobs(jobs, args);
  // Partition of unity at scale: run on their own (--only pu3d), they take a while.
  for (const auto& [label, N] : {std::pair<const char*, int>{"1e5", 100000}, {"1e6", 1000000}}) {
    const int n = args.quick ? N / 100 : N;
    jobs.emplace_back(std::string("pu3d/two-tori/N=") + label, [n, label = std::string(label)] { return benchPuTori(n, label); });
  }
}

// Runs the jobs `args.only` selects and prints their results (a table, or JSON with --json).
int runJobs(Jobs& jobs, const BenchArgs& args) {
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
    out["blas_core"] = blasCoreName();
    json arr = json::array();
    for (const Result& r : results)
      arr.push_back({{"name", r.name}, {"params", r.params}, {"median", r.median}, {"unit", r.unit}});
    out["results"] = std::move(arr);
    writeStdout(out.dump(2) + "\n");
  } else {
    writeStdout("cores " + std::to_string(availableCores()) + ", threads " + std::to_string(threadCount()) +
                ", OpenBLAS core " + blasCoreName() + "\n");
  }
  return 0;
}

}  // namespace

int runBench(const BenchArgs& args) {
  Jobs jobs;
  addFitJobs(jobs, args);
  addMeshJobs(jobs, args);
  addRenderJobs(jobs, args);
  return runJobs(jobs, args);
}

}  // namespace hermite::app
