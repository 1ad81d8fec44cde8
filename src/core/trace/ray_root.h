#pragma once
// The root finder both 3D tracers share: the first zero of f along a ray, found by probing for a
// sign change and narrowing the bracket by bisection. The CPU reference tracer (cpu_tracer.h)
// chooses its own probes (safe Lipschitz steps) and feeds the values in as its wavefront gets
// them; the GPU tracer's refinement (render/hit_refinement.h) probes evenly spaced samples
// through refineRayRoot.

#include <optional>

#include "core/base/implicit_field.h"
#include "core/trace/camera.h"

namespace hermite {

// How a probe reads a value of exactly 0 or NaN. The two tracers read such probes differently;
// each keeps its own reading, so that sharing the routine changes none of their images.
enum class ZeroRule {
  // The CPU reference tracer: f = 0 at a probe is the root. A sign change needs two non-zero
  // values of opposite sign (a NaN opens no bracket); inside a bracket a NaN counts as past the root.
  StopAtZero,
  // The GPU tracer's refinement: only f < 0 is negative, so NaN reads as positive; f = 0 at a
  // probe counts as past the root, so bisection closes in on the first zero of a flat stretch.
  ZeroIsPast,
};

// What one probe says about the first root after the previous probe.
enum class ProbeVerdict {
  NoChange,   // f keeps its side: the root, if any, lies further along
  SignChange, // f changed sides since the previous probe: bisect between the two
  Root,       // f = 0 at the probe, and the rule takes it as the root
};

// The verdict on a probe with value f after a probe with value previous.
ProbeVerdict judgeProbe(double previous, double f, ZeroRule rule);

// A bracket [lo, hi] of the ray parameter across which f changes sides, narrowed by bisection
// one probe at a time, so that a caller can batch the probes of many rays.
class RootBracket {
 public:
  RootBracket(double lo, double fLo, double hi, ZeroRule rule)
      : lo_(lo), hi_(hi), negativeLo_(fLo < 0), rule_(rule) {}

  // Where f is wanted next: the midpoint.
  double probe() const { return 0.5 * (lo_ + hi_); }
  // True once the bracket is at most `tolerance` long, or no double lies between its ends (so a
  // tolerance below the spacing of doubles still ends); probe() is then the root.
  bool settled(double tolerance) const {
    const double m = probe();
    return hi_ - lo_ <= tolerance || m == lo_ || m == hi_;
  }
  // Narrows the bracket with f at probe(). True when the rule takes probe() as the root
  // (StopAtZero and f = 0); the bracket then stays as it is.
  bool narrow(double f);

  double lo() const { return lo_; }
  double hi() const { return hi_; }

 private:
  double lo_, hi_;
  bool negativeLo_;  // f(lo) < 0
  ZeroRule rule_;
};

struct RayRootOptions {
  int samples = 16;        // evenly spaced probes over [lo, hi] (after lo itself) looking for a sign change
  double tolerance = 0;    // bisection stops when the bracket is this short (ray parameter units;
                           // 0: when its ends are neighbouring doubles)
  ZeroRule rule = ZeroRule::ZeroIsPast;
};

// The first zero of f along `ray` with lo ≤ t ≤ hi: f is probed at lo and at `samples` even steps
// up to hi, and the first sign change between neighbouring probes is bisected to `tolerance`.
// Empty when no probe pair changes sign (a root between two probes on the same side is missed).
std::optional<double> refineRayRoot(const ImplicitField<3>& field, const Ray& ray, double lo, double hi,
                                    const RayRootOptions& options);

}  // namespace hermite
