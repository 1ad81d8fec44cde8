#pragma once
// The CPU reference tracer: ground-truth images of any ImplicitField<3> for tests and for
// checking the GPU tracers (docs/maths.md, Volume bake and sphere tracing). Each pixel's ray
// (Camera) is clipped to the bounds box and marched with safe steps max(|f|/L, ε), L a Lipschitz
// bound of f over the brick the ray is in (bricks proven free of zeros are skipped); the first
// sign change is refined by bisection (ray_root.h, shared with the GPU tracer's refinement).
// Every zero-set component inside the bounds thicker than ε is found.

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/implicit_field.h"
#include "core/trace/camera.h"
#include "core/trace/image.h"
#include "core/trace/volume_bake.h"

namespace hermite {

struct CpuTraceOptions {
  double minStep = 1e-4;          // ε, relative to the bounds diagonal: thinner features may be missed
  double refineTolerance = 1e-7;  // bisection stops at this interval, relative to the bounds diagonal
  int bricksPerAxis = 16;         // Lipschitz bounds on this many boxes per axis (finer: longer steps, more set-up)
};

struct CpuTraceResult {
  ImageRgba8 image;                  // W × H, row 0 = top; misses are exactly round(255·background)
  std::vector<std::uint8_t> hit;     // W·H, 1 where the ray hits the zero set inside the bounds
  std::vector<std::uint8_t> back;    // W·H, 1 where the hit is from inside (dot(∇f, dir) > 0)
  std::vector<float> depth;          // W·H, ray parameter t of the hit (world units; +inf on a miss)
  std::vector<float> normal;         // 3·W·H, outward unit ∇f/‖∇f‖ at the hit (0 on a miss)
  double setupMs = 0;                // brick Lipschitz bounds
  double traceMs = 0;                // rays, wall clock
  long long evaluations = 0;         // f evaluations of all rays (stepping + refinement)

  Vec<3> normalAt(int i, int j) const {
    const std::size_t p = std::size_t(j) * image.width + i;
    return Vec<3>(normal[3 * p], normal[3 * p + 1], normal[3 * p + 2]);
  }
};

// Result of tracing one ray.
struct RayHit {
  bool hit = false;
  double t = 0;                        // ray parameter
  Vec<3> position = Vec<3>::Zero();
  Vec<3> normal = Vec<3>::Zero();      // outward unit normal (−dir if ∇f = 0 there)
  bool back = false;
  int evaluations = 0;
};

// Reusable tracer: the brick bounds are computed once per field and bounds. render() traces all
// pixels as a wavefront (one batched f evaluation per round) and gives the same hits as trace().
class CpuTracer {
 public:
  // Throws InputError for empty or non-finite bounds or invalid options.
  CpuTracer(const ImplicitField<3>& field, const Box<3>& bounds, const CpuTraceOptions& options = {});

  // The first zero of f along the ray with t ≥ 0 inside the bounds.
  RayHit trace(const Ray& ray) const;
  // Whole image, threaded over rows; background each in [0, 1].
  CpuTraceResult render(const Camera& camera, const std::array<double, 3>& background) const;

  double setupMs() const { return setupMs_; }

 private:
  struct RayState;
  RayState start(const Ray& ray) const;
  double nextMarch(const RayState& s) const;
  void advance(RayState& s, double value) const;
  RayHit finish(const RayState& s, const Vec<3>& gradient) const;
  // render()'s steps: every pixel's ray started; all rays advanced in rounds of one batched f
  // evaluation (a wavefront) until each hits or misses; ∇f at the hits in one batch (zero
  // elsewhere); the pixels shaded into out, returning the f evaluations of all rays.
  std::vector<RayState> startRays(const Camera& camera) const;
  void marchWavefront(std::vector<RayState>& states) const;
  std::vector<Vec<3>> hitGradients(const std::vector<RayState>& states) const;
  long long shadePixels(const std::vector<RayState>& states, const std::vector<Vec<3>>& gradient, const Camera& camera,
                        const std::array<double, 3>& background, CpuTraceResult& out) const;

  const ImplicitField<3>& field_;
  Box<3> bounds_;
  CpuTraceOptions options_;
  BrickGrid grid_;
  double diagonal_ = 0;
  double setupMs_ = 0;
};

// One-shot form.
CpuTraceResult traceImage(const ImplicitField<3>& field, const Camera& camera, const Box<3>& bounds,
                          const std::array<double, 3>& background, const CpuTraceOptions& options = {});

}  // namespace hermite
