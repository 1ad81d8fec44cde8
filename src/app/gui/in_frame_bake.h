#pragma once
// The coarse bake a drag's own frame makes (docs/design.md, Threads; issue 18: a drag's refit on
// screen within a frame or two). The view worker's 64³ bake of each refit arrives 13–20 frames
// after the move on 2 cores; a 16³–32³ bake of a small RadialSum model (HRBF, RBF-offset) costs
// a few milliseconds, so the GUI thread makes it itself in the frame the refit arrives in and the
// worker's finer bake replaces it later (coarse, then fine; the newest fit wins).
//
// Sized before it starts: the cost is R³ · (centres + overhead) terms at the time per term this
// thread measured on its last bake (a start value before the first); the largest R of 32, 24 and
// 16 expected within the budget is baked, none when even 16³ is not (the worker's bake then comes
// as before). Each refusal lowers the time per term by 10 %, not below the fastest one measured,
// so that one slow bake under a passing load spike does not turn the in-frame bakes off for good
// while a model too large for the budget never gets one.

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "render/implicit_tracer.h"

namespace hermite::app {

class InFrameBake {
 public:
  // Wall clock one bake may take in the frame (a frame that carries a drag refit may take 50 ms).
  static constexpr double kBudgetMs = 10.0;

  // The largest bake resolution R (32, 24 or 16) expected within kBudgetMs for `field`; 0 when
  // none is, or when the field is no RadialSum (its cost per sample is unknown).
  int resolutionFor(const ImplicitField<3>& field);
  // Bakes `field` over `bounds` at R samples per axis on this thread (OpenMP; 8 cells per brick as
  // the worker's bakes) and learns its cost.
  render::TracerVolume bake(const ImplicitField<3>& field, const Box<3>& bounds, int resolution);
  // Expected wall clock of a bake of `field` at R (ms); infinity for fields that are no RadialSum.
  double estimateMs(const ImplicitField<3>& field, int resolution) const;

 private:
  // Wall clock per term (ms; a sample's terms are its centres plus an overhead for the
  // polynomial, the bricks and the normals). Start value: a 250-centre cubic HRBF baked at 32³ in
  // 16–60 ms on a 2-core machine under load 7 without AVX-512, 2–7e-6 ms per term; quiet it is
  // several times less. Each bake replaces it with what it measured.
  double msPerTerm_ = 1.0e-6;
  double fastestMsPerTerm_ = 1.0e-6;
};

}  // namespace hermite::app
