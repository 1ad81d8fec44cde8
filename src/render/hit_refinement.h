#pragma once
// The GPU tracer's exact refinement on the CPU: the GPU pass marches the bake, so its hits are
// only as good as the bake; here each of them is refined against the true field along the
// pixel's Camera ray, so settled views show the field's own surface and normals (docs/design.md,
// Rendering). Limitation: a component the bake misses entirely (thinner than about one bake cell)
// stays missing away from the silhouette of a found surface; refinement only corrects what the
// bake found, plus the one-pixel ring around it.

#include <cstdint>
#include <functional>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"
#include "core/trace/camera.h"
#include "core/trace/volume_bake.h"

namespace hermite::render {

// One frame of the GPU trace pass, row 0 = top, as refineHits reads it.
struct GpuHits {
  const std::vector<float>& t;       // W·H: surface hit's ray parameter ≥ 0, −1 a miss, < −1.5 undecided
  const std::vector<float>& normal;  // 3·W·H: the GPU's unit normals at its hits
  const std::vector<int>& undecided; // the pixels whose march ran out of steps or loop budget
};

struct HitRefinement;

struct HitRefinementOptions {
  bool refine = true;     // false: GPU hits stand as they are; only the undecided pixels are traced
  double cell = 0;        // the bake's cell diagonal: how far from the GPU's t a hit is looked for
  double cpuMinStep = 1e-4;  // ε of the CPU tracer for undecided pixels, relative to the bounds diagonal
  // The bake the GPU marched (null: none). Where the field can lack data, a GPU hit the true field
  // does not confirm (a zero without data the bake's filtered marks let through, at the rim of an
  // open scan) is followed on along its ray through it, each sign change of its interpolant
  // checked with the true field, so the pixel shows what lies behind instead of nothing.
  const VolumeBake* bake = nullptr;
  // Polled between bands of rows (each a few tens of ms of work); throws Cancelled when set.
  const CancelToken* cancel = nullptr;
  int bandRows = 16;  // rows refined per band
  // Called after each band with the refinement so far: rows [rowBegin, rowEnd) (row 0 = top) of
  // it are final (the progressive window view publishes them); may be empty.
  std::function<void(const HitRefinement& partial, int rowBegin, int rowEnd)> onBand;
};

// The surface per pixel after refinement, row 0 = top.
struct HitRefinement {
  std::vector<double> t;            // ray parameter of the surface hit; < 0 where there is none
  std::vector<Vec<3>> gradient;     // ∇f at the hit (the GPU's normal where its hit stands unrefined)
  std::vector<std::uint8_t> gpuHit; // 1 where the GPU pass found a hit
  int ringHits = 0;                 // silhouette-ring pixels that gained a hit
  int droppedHits = 0;              // GPU hits the true field does not confirm (now misses)
};

// Refines the GPU's hits band of rows by band of rows, each in four steps: safeguarded Newton on
// f along the ray from the GPU's t (batched over pixels); a bracket search with bisection within
// 2 cells of it where Newton does not settle (hits it finds nothing for are dropped, or followed
// on through the bake, above); the CPU reference tracer for undecided pixels; and, with
// `refine`, a bracket search on the misses next to a hit (the silhouette ring) near their
// neighbours' depth, so thin rims the bake loses come back.
HitRefinement refineHits(const ImplicitField<3>& field, const Box<3>& bounds, const Camera& camera, const GpuHits& gpu,
                         const HitRefinementOptions& options);

}  // namespace hermite::render
