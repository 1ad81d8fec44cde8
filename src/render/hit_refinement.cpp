#include "render/hit_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/trace/cpu_tracer.h"
#include "core/trace/ray_root.h"

namespace hermite::render {

namespace {

// A GPU hit pixel's ray, the current guess of its surface parameter and the ray's clip to the bounds.
struct PixelRay {
  int pixel;
  Ray ray;
  double t;
  double tLo, tHi;
};

// A stretch [lo, hi] of a pixel's ray where the bracket search looks for the surface.
struct SearchWindow {
  int pixel;
  Ray ray;
  double lo, hi;
};

// The refinement's shared state: the inputs, and the output it fills in.
struct Refiner {
  const ImplicitField<3>& field;
  const Box<3>& bounds;
  const Camera& camera;
  const GpuHits& gpu;
  const HitRefinementOptions& options;
  double tol;  // bisection and Newton stop at this many world units along the ray
  HitRefinement& out;
  int p0 = 0, p1 = 0;  // the band: pixels p0 … p1 − 1 (whole rows)

  Ray pixelRay(int p) const { return camera.pixelRay(p % camera.width(), p / camera.width()); }
  // A root counts only where the field has data on its zero set (validOnZeroSet, as the mesher's
  // vertices; a flat-masked field, a partition of unity's edge): elsewhere its f ≈ 0 is noise,
  // which the bake marks for the march to pass too.
  bool hasData(const Vec<3>& x) const { return field.everywhereValid() || field.validOnZeroSet(x); }
  std::vector<PixelRay> seedHits();
  std::vector<PixelRay> newton(std::vector<PixelRay> active);
  int searchWindows(const std::vector<SearchWindow>& windows);
  std::optional<double> rootIn(const Ray& ray, double lo, double hi) const;
  void storeHit(int pixel, const Ray& ray, double t);
  int searchUnsettled(const std::vector<PixelRay>& unsettled);
  void followOnward(const std::vector<SearchWindow>& dropped);
  void traceUndecided();
  std::vector<SearchWindow> silhouetteRing() const;
};

// Marks the GPU's hits. With refinement off they stand as they are (the refinement then runs only
// for the undecided pixels); else each becomes a ray for Newton, starting at the GPU's t.
std::vector<PixelRay> Refiner::seedHits() {
  std::vector<PixelRay> work;
  work.reserve(gpu.t.size() / 4);
  for (std::size_t p = std::size_t(p0); p < std::size_t(p1); ++p) {
    if (gpu.t[p] < 0) continue;
    out.gpuHit[p] = 1;
    if (!options.refine) {
      out.t[p] = gpu.t[p];
      out.gradient[p] = Vec<3>(gpu.normal[3 * p], gpu.normal[3 * p + 1], gpu.normal[3 * p + 2]);
      continue;
    }
    const Ray ray = pixelRay(int(p));
    double a = 0, b = 0;
    clipRayToBox(ray, bounds, a, b);
    work.push_back({int(p), ray, double(gpu.t[p]), a, b});
  }
  return work;
}

// Safeguarded Newton along each ray, batched over the pixels (one evaluateBatch of f and ∇f per
// iteration). Returns the pixels it does not settle in 4 iterations: those whose step is longer
// than 2 cells or leaves the bounds, or meets a non-finite f, go to the bracket search instead.
std::vector<PixelRay> Refiner::newton(std::vector<PixelRay> active) {
  const double cell = options.cell;
  std::vector<PixelRay> unsettled;
  Points<3> X;
  Points<3> G;
  Eigen::VectorXd F;
  for (int iteration = 0; iteration < 4 && !active.empty(); ++iteration) {
    X.resize(3, Eigen::Index(active.size()));
    for (std::size_t q = 0; q < active.size(); ++q) X.col(Eigen::Index(q)) = active[q].ray.at(active[q].t);
    field.evaluateBatch(X, F, &G);
    std::vector<PixelRay> next;
    for (std::size_t q = 0; q < active.size(); ++q) {
      PixelRay& w = active[q];
      const Vec<3> g = G.col(Eigen::Index(q));
      const double f = F(Eigen::Index(q));
      const double fd = g.dot(w.ray.direction);
      const double stepLength = fd != 0 ? f / fd : std::numeric_limits<double>::infinity();
      const double tn = w.t - stepLength;
      if (!std::isfinite(stepLength) || std::abs(stepLength) > 2 * cell || tn < w.tLo - tol || tn > w.tHi + tol ||
          !std::isfinite(f)) {
        unsettled.push_back(w);
        continue;
      }
      if (std::abs(stepLength) <= tol || f == 0) {
        if (!hasData(w.ray.at(tn))) {
          unsettled.push_back(w);  // the bracket search drops it unless it finds a root with data
          continue;
        }
        out.t[w.pixel] = std::clamp(tn, w.tLo, w.tHi);
        out.gradient[w.pixel] = g;
        continue;
      }
      w.t = tn;
      (iteration == 3 ? unsettled : next).push_back(w);
    }
    active.swap(next);
  }
  return unsettled;
}

// Searches every window with the true field (16 probes over [lo, hi], then bisection to tol,
// ray_root.h) and stores each hit found with its gradient; returns how many it found.
int Refiner::searchWindows(const std::vector<SearchWindow>& windows) {
  int found = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : found)
  for (std::size_t q = 0; q < windows.size(); ++q) {
    const SearchWindow& w = windows[q];
    const std::optional<double> t = rootIn(w.ray, w.lo, w.hi);
    if (!t || !hasData(w.ray.at(*t))) continue;
    storeHit(w.pixel, w.ray, *t);
    ++found;
  }
  return found;
}

// The first zero of the true field on the ray within [lo, hi]: 16 probes, then bisection to tol.
std::optional<double> Refiner::rootIn(const Ray& ray, double lo, double hi) const {
  RayRootOptions search;
  search.samples = 16;
  search.tolerance = tol;
  search.rule = ZeroRule::ZeroIsPast;
  return refineRayRoot(field, ray, lo, hi, search);
}

// The pixel's hit at ray parameter t, with ∇f there.
void Refiner::storeHit(int pixel, const Ray& ray, double t) {
  Vec<3> g;
  field.evaluate(ray.at(t), &g);
  out.t[pixel] = t;
  out.gradient[pixel] = g;
}

// Looks for the surface within 2 cells of the GPU's t where Newton did not settle; returns how
// many GPU hits the true field does not confirm there. Where the field can lack data, such a hit
// is often a zero without data that the bake's filtered marks let through (the rim of an open
// scan): followOnward then goes on along the ray past it.
int Refiner::searchUnsettled(const std::vector<PixelRay>& unsettled) {
  std::vector<SearchWindow> windows;
  windows.reserve(unsettled.size());
  for (const PixelRay& w : unsettled) {
    const double t = gpu.t[w.pixel];
    windows.push_back({w.pixel, w.ray, std::max(w.tLo, t - 2 * options.cell), std::min(w.tHi, t + 2 * options.cell)});
  }
  const int dropped = int(unsettled.size()) - searchWindows(windows);
  if (dropped > 0 && !field.everywhereValid() && options.bake) {
    std::vector<SearchWindow> onward;
    for (const SearchWindow& w : windows)
      if (out.t[w.pixel] < 0) onward.push_back(w);
    followOnward(onward);
  }
  return dropped;
}

// The first sign change of the bake's interpolant on the ray after `from` (steps of half a
// sample spacing, up to `to`), as the bracket [a, b]; false when there is none.
bool nextBakeSignChange(const VolumeBake& bake, const Ray& ray, double from, double to, double& a, double& b) {
  const double step = 0.5 * bake.spacing().minCoeff();
  double t = from, f = bake.interpolate(ray.at(t));
  while (t < to) {
    const double tn = std::min(to, t + step), fn = bake.interpolate(ray.at(tn));
    if ((f < 0) != (fn < 0)) {
      a = t;
      b = tn;
      return true;
    }
    t = tn;
    f = fn;
  }
  return false;
}

// Follows each dropped hit's ray on from the GPU's t through the bake: every sign change of the
// interpolant is searched with the true field within 2 cells (as a GPU hit is), and the first
// root with data is the pixel's hit; past a root without data the walk goes on from that root
// (or the sign change, if later), so a surface just behind it (the inside, a cell past the rim)
// is not skipped. At most kOnwardWindows windows a ray: what the march would pass again. Polls
// the cancel token per ray (a band can hold thousands of them) and throws Cancelled after.
void Refiner::followOnward(const std::vector<SearchWindow>& dropped) {
  constexpr int kOnwardWindows = 8;
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t q = 0; q < dropped.size(); ++q) {
    if (options.cancel && options.cancel->cancelled()) continue;
    const int p = dropped[q].pixel;
    const Ray& ray = dropped[q].ray;
    double lo = 0, hi = 0, a = 0, b = 0;
    if (!clipRayToBox(ray, bounds, lo, hi)) continue;
    double from = std::max(lo, double(gpu.t[p]));
    for (int w = 0; w < kOnwardWindows && nextBakeSignChange(*options.bake, ray, from, hi, a, b); ++w) {
      const double wLo = std::max(lo, a - 2 * options.cell), wHi = std::min(hi, b + 2 * options.cell);
      const std::optional<double> t = rootIn(ray, std::max(from, wLo), wHi);
      if (t && hasData(ray.at(*t))) {
        storeHit(p, ray, *t);
        break;
      }
      from = t ? std::max(b, *t + 4 * tol) : b;
    }
  }
  throwIfCancelled(options.cancel);
}

// Traces the pixels the GPU march left undecided with the CPU reference tracer, whose ε matches
// the exact march's.
void Refiner::traceUndecided() {
  std::vector<int> band;
  for (int p : gpu.undecided)
    if (p >= p0 && p < p1) band.push_back(p);
  if (band.empty()) return;
  CpuTraceOptions cpuOptions;
  cpuOptions.minStep = options.cpuMinStep;
  const CpuTracer cpu(field, bounds, cpuOptions);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t q = 0; q < band.size(); ++q) {
    const int p = band[q];
    const RayHit hit = cpu.trace(pixelRay(p));
    if (hit.hit) {
      out.t[p] = hit.t;
      out.gradient[p] = hit.normal;
    }
  }
}

// The silhouette ring: pixels without a GPU hit that have one among their 8 neighbours, each
// searched within 2 cells of those neighbours' ray parameters (inside the bounds).
std::vector<SearchWindow> Refiner::silhouetteRing() const {
  const int W = camera.width(), H = camera.height();
  std::vector<SearchWindow> ring;
  for (int j = p0 / W; j < p1 / W; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t p = std::size_t(j) * W + i;
      if (out.gpuHit[p]) continue;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= W || jj >= H) continue;
          const float t = gpu.t[std::size_t(jj) * W + ii];
          if (t < 0) continue;
          lo = std::min(lo, double(t));
          hi = std::max(hi, double(t));
        }
      if (!(lo <= hi)) continue;
      const Ray ray = camera.pixelRay(i, j);
      double a, b;
      if (!clipRayToBox(ray, bounds, a, b)) continue;
      const double from = std::max(a, lo - 2 * options.cell), to = std::min(b, hi + 2 * options.cell);
      if (from < to) ring.push_back({int(p), ray, from, to});
    }
  return ring;
}

}  // namespace

HitRefinement refineHits(const ImplicitField<3>& field, const Box<3>& bounds, const Camera& camera, const GpuHits& gpu,
                         const HitRefinementOptions& options) {
  const std::size_t pixels = gpu.t.size();
  HitRefinement out;
  out.t.assign(pixels, -1.0);
  out.gradient.assign(pixels, Vec<3>::Zero());
  out.gpuHit.assign(pixels, 0);
  Refiner refiner{field, bounds, camera, gpu, options, 1e-7 * bounds.extent().norm(), out};
  const int W = camera.width(), H = camera.height(), band = std::max(1, options.bandRows);
  for (int j0 = 0; j0 < H; j0 += band) {
    throwIfCancelled(options.cancel);
    refiner.p0 = j0 * W;
    refiner.p1 = std::min(H, j0 + band) * W;
    const std::vector<PixelRay> unsettled = refiner.newton(refiner.seedHits());
    out.droppedHits += refiner.searchUnsettled(unsettled);
    // The CPU-traced undecided pixels come before the ring, which may overwrite those next to a hit.
    refiner.traceUndecided();
    if (options.refine) out.ringHits += refiner.searchWindows(refiner.silhouetteRing());
    if (options.onBand) options.onBand(out, j0, std::min(H, j0 + band));
  }
  return out;
}

}  // namespace hermite::render
