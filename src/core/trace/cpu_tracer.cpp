#include "core/trace/cpu_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/trace/ray_root.h"
#include "core/trace/shading.h"

namespace hermite {

namespace {

// Parameter where the ray leaves the box (rays start inside or on it).
double exitParameter(const Ray& ray, const Box<3>& box) {
  double t = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double d = ray.direction(k);
    if (d > 0) t = std::min(t, (box.hi(k) - ray.origin(k)) / d);
    if (d < 0) t = std::min(t, (box.lo(k) - ray.origin(k)) / d);
  }
  return t;
}

}  // namespace

CpuTracer::CpuTracer(const ImplicitField<3>& field, const Box<3>& bounds, const CpuTraceOptions& options)
    : field_(field), bounds_(bounds), options_(options) {
  if (!(options.minStep > 0) || !(options.refineTolerance > 0) || options.bricksPerAxis < 1)
    throw InputError("cpu tracer: minStep and refineTolerance must be > 0, bricksPerAxis ≥ 1");
  const auto t0 = std::chrono::steady_clock::now();
  grid_ = computeBrickGrid(field, bounds, Eigen::Array3i::Constant(options.bricksPerAxis));
  diagonal_ = bounds.extent().norm();
  setupMs_ = msSince(t0);
}

// One ray's progress, advanced one f evaluation at a time, so rays can be traced alone or as a
// wavefront whose evaluations are batched (evaluateBatch vectorises over the centres).
struct CpuTracer::RayState {
  enum Phase : std::uint8_t { March, Bisect, Hit, Miss };
  Ray ray;
  double t = 0, t1 = 0;    // current point and the exit of the bounds
  double fa = 0;           // f at t (valid after the first evaluation)
  RootBracket bracket{0, 0, 0, ZeroRule::StopAtZero};  // the sign change, during bisection
  double query = 0;        // parameter whose f value advance() expects next
  long long steps = 0;
  bool started = false;
  Phase phase = Miss;
};

CpuTracer::RayState CpuTracer::start(const Ray& ray) const {
  RayState s;
  s.ray = ray;
  double t0 = 0.0, t1 = 0.0;
  if (!clipRayToBox(ray, bounds_, t0, t1)) return s;
  s.t = s.query = t0;
  s.t1 = t1;
  s.phase = RayState::March;
  return s;
}

double CpuTracer::nextMarch(const RayState& s) const {
  const double eps = options_.minStep * diagonal_;
  const double nudge = 1e-9 * diagonal_;  // past a brick face, so the next brick is found
  const Ray& ray = s.ray;
  const double t = s.t;
  const Eigen::Array3i b = grid_.locate(ray.at(std::min(t + nudge, s.t1)));
  const int brick = grid_.index(b.x(), b.y(), b.z());
  const double tExit = std::min(std::max(exitParameter(ray, grid_.brickBox(b.x(), b.y(), b.z())), t + nudge), s.t1);
  if (!grid_.mayContainZero[brick]) return tExit;  // proven zero-free: skip the brick
  // f cannot reach zero within |f|/L while the ray stays in the brick (L bounds ‖∇f‖ there).
  const double L = grid_.lipschitz[brick];
  const double step = L > 0 ? std::abs(s.fa) / L : std::numeric_limits<double>::infinity();
  return (t + step >= tExit) ? tExit : std::min(t + std::max(eps, step), s.t1);
}

void CpuTracer::advance(RayState& s, double value) const {
  const double tol = options_.refineTolerance * diagonal_;
  ++s.steps;
  auto hitAt = [&](double t) {
    // A zero where the field has no data, on either side of the root (the jump of f to its
    // no-data value at the edge of the data), or a root the field does not accept on its zero set
    // (validOnZeroSet, as the mesher's vertices), is no surface: the ray passes it and marches on
    // from just beyond (an open scan seen through its opening shows its inside), as the GPU
    // tracer's march does.
    const double before = s.phase == RayState::Bisect ? s.bracket.lo() : s.t;
    if (!field_.everywhereValid() && !(field_.validOnZeroSet(s.ray.at(t)) && field_.valid(s.ray.at(before)))) {
      const double past = std::max(t + tol, s.phase == RayState::Bisect ? s.bracket.hi() : t + tol);
      if (past >= s.t1) {
        s.phase = RayState::Miss;
        return;
      }
      s.t = s.query = past;
      s.started = false;  // f at `past` restarts the march
      s.phase = RayState::March;
      return;
    }
    s.t = t;
    s.phase = RayState::Hit;
  };
  auto bisectOrFinish = [&]() {
    if (s.bracket.settled(tol))
      hitAt(s.bracket.probe());
    else
      s.query = s.bracket.probe();
  };
  if (s.phase == RayState::March) {
    if (!s.started) {
      s.started = true;
      s.fa = value;
      if (value == 0) return hitAt(s.t);
    } else {
      switch (judgeProbe(s.fa, value, ZeroRule::StopAtZero)) {
        case ProbeVerdict::Root: return hitAt(s.query);
        case ProbeVerdict::SignChange:
          s.bracket = RootBracket(s.t, s.fa, s.query, ZeroRule::StopAtZero);
          s.phase = RayState::Bisect;
          return bisectOrFinish();
        case ProbeVerdict::NoChange:
          s.t = s.query;
          s.fa = value;
          break;
      }
    }
    if (s.t >= s.t1 || s.steps > 10'000'000) {
      s.phase = RayState::Miss;
      return;
    }
    s.query = nextMarch(s);
  } else if (s.phase == RayState::Bisect) {
    if (s.bracket.narrow(value)) return hitAt(s.query);
    bisectOrFinish();
  }
}

RayHit CpuTracer::finish(const RayState& s, const Vec<3>& gradient) const {
  RayHit result;
  result.evaluations = int(std::min<long long>(s.steps, 1 << 30));
  if (s.phase != RayState::Hit) return result;
  result.hit = true;
  result.t = s.t;
  result.position = s.ray.at(s.t);
  const double gn = gradient.norm();
  result.normal = (gn > 0 && std::isfinite(gn)) ? Vec<3>(gradient / gn) : Vec<3>(-s.ray.direction);
  result.back = result.normal.dot(s.ray.direction) > 0;
  return result;
}

RayHit CpuTracer::trace(const Ray& ray) const {
  RayState s = start(ray);
  while (s.phase == RayState::March || s.phase == RayState::Bisect) advance(s, field_.evaluate(s.ray.at(s.query)));
  Vec<3> g = Vec<3>::Zero();
  if (s.phase == RayState::Hit) field_.evaluate(s.ray.at(s.t), &g);
  RayHit h = finish(s, g);
  h.evaluations += h.hit ? 1 : 0;
  return h;
}

// Every pixel's ray clipped to the bounds (Miss where it passes by them).
std::vector<CpuTracer::RayState> CpuTracer::startRays(const Camera& camera) const {
  const int W = camera.width(), H = camera.height();
  const std::size_t n = std::size_t(W) * H;
  std::vector<RayState> states(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < std::ptrdiff_t(n); ++p)
    states[p] = start(camera.pixelRay(int(p % W), int(p / W)));
  return states;
}

// Wavefront: every live ray asks for one f value per round; the values come from one
// evaluateBatch call (threaded and vectorised), then the rays advance in parallel.
void CpuTracer::marchWavefront(std::vector<RayState>& states) const {
  std::vector<std::ptrdiff_t> live;
  for (std::size_t p = 0; p < states.size(); ++p)
    if (states[p].phase != RayState::Miss) live.push_back(std::ptrdiff_t(p));
  Points<3> X;
  Eigen::VectorXd f;
  while (!live.empty()) {
    const std::ptrdiff_t m = std::ptrdiff_t(live.size());
    X.resize(3, m);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t q = 0; q < m; ++q) X.col(q) = states[live[q]].ray.at(states[live[q]].query);
    field_.evaluateBatch(X, f);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t q = 0; q < m; ++q) advance(states[live[q]], f(q));
    std::size_t kept = 0;
    for (std::ptrdiff_t q = 0; q < m; ++q) {
      const RayState& s = states[live[q]];
      if (s.phase == RayState::March || s.phase == RayState::Bisect) live[kept++] = live[q];
    }
    live.resize(kept);
  }
}

// ∇f at every hit, in one batch; zero for the other rays.
std::vector<Vec<3>> CpuTracer::hitGradients(const std::vector<RayState>& states) const {
  std::vector<std::ptrdiff_t> hits;
  for (std::size_t p = 0; p < states.size(); ++p)
    if (states[p].phase == RayState::Hit) hits.push_back(std::ptrdiff_t(p));
  Points<3> X(3, std::ptrdiff_t(hits.size()));
  for (std::size_t q = 0; q < hits.size(); ++q) X.col(std::ptrdiff_t(q)) = states[hits[q]].ray.at(states[hits[q]].t);
  Eigen::VectorXd f;
  Points<3> G;
  field_.evaluateBatch(X, f, &G);
  std::vector<Vec<3>> gradient(states.size(), Vec<3>::Zero());
  for (std::size_t q = 0; q < hits.size(); ++q) gradient[hits[q]] = G.col(std::ptrdiff_t(q));
  return gradient;
}

// Writes each pixel (background on a miss) and its hit, depth and normal; returns all rays' f evaluations.
long long CpuTracer::shadePixels(const std::vector<RayState>& states, const std::vector<Vec<3>>& gradient,
                                 const Camera& camera, const std::array<double, 3>& background,
                                 CpuTraceResult& out) const {
  const std::uint8_t bg[3] = {shading::toByte(background[0]), shading::toByte(background[1]),
                              shading::toByte(background[2])};
  long long evaluations = 0;
#pragma omp parallel for schedule(static) reduction(+ : evaluations)
  for (std::ptrdiff_t p = 0; p < std::ptrdiff_t(states.size()); ++p) {
    const RayHit h = finish(states[p], gradient[p]);
    evaluations += states[p].steps + (h.hit ? 1 : 0);
    std::uint8_t* px = out.image.pixels.data() + 4 * p;
    px[3] = 255;
    if (!h.hit) {
      px[0] = bg[0];
      px[1] = bg[1];
      px[2] = bg[2];
      continue;
    }
    out.hit[p] = 1;
    out.back[p] = h.back ? 1 : 0;
    out.depth[p] = float(h.t);
    for (int k = 0; k < 3; ++k) out.normal[3 * p + k] = float(h.normal(k));
    const Vec<3> c = shading::shadeHit(h.normal, states[p].ray.direction, camera.right(), camera.up(), camera.forward());
    for (int k = 0; k < 3; ++k) px[k] = shading::toByte(c(k));
  }
  return evaluations;
}

CpuTraceResult CpuTracer::render(const Camera& camera, const std::array<double, 3>& background) const {
  const int W = camera.width(), H = camera.height();
  const std::size_t n = std::size_t(W) * H;
  CpuTraceResult out;
  out.image = ImageRgba8(W, H);
  out.hit.assign(n, 0);
  out.back.assign(n, 0);
  out.depth.assign(n, std::numeric_limits<float>::infinity());
  out.normal.assign(3 * n, 0.0f);
  out.setupMs = setupMs_;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<RayState> states = startRays(camera);
  marchWavefront(states);
  const std::vector<Vec<3>> gradient = hitGradients(states);
  out.evaluations = shadePixels(states, gradient, camera, background, out);
  out.traceMs = msSince(t0);
  return out;
}

CpuTraceResult traceImage(const ImplicitField<3>& field, const Camera& camera, const Box<3>& bounds,
                          const std::array<double, 3>& background, const CpuTraceOptions& options) {
  return CpuTracer(field, bounds, options).render(camera, background);
}

}  // namespace hermite
