#pragma once
// The patch editor's document (scene key `patch` of a `"mode": "patch"` scene): a C¹
// grid of bicubic Hermite patches over knots u₀ < … < uₙ, v₀ < … < vₘ, defined by data at the
// knots (X, Xu, Xv, Xuv; docs/maths.md, Patches). Presets generate the data; edits change it; every patch
// that shares a knot sees the edit, so C¹ continuity holds by construction.
//
// Handles, in either form, are edits of the knot data:
//   Hermite: per knot, the point X and the tips X + ℓu·Xu, X + ℓv·Xv and the twist tip
//            X + ℓu·Xu + ℓv·Xv + ℓu·ℓv·Xuv, with ℓ = a third of the mean knot spacing (so on
//            uniform knots the tips sit on the Bézier control points next to the corner);
//   Bézier:  per patch, the 16 control points; moving one is the Hermite edit that keeps the
//            patch's other 15 control points where they are: the corner's four control points
//            (corner c, its s- and t-neighbours and the inner one) determine that corner's
//            X = c, Xs = 3σs(s − c), Xt = 3σt(t − c), Xst = 9σsσt(i − s − t + c), σ = ±1 by side.

#include <array>
#include <string>
#include <vector>

#include "core/patch/patch_grid.h"
#include "core/base/enum_names.h"

namespace hermite {

enum class PatchForm { Hermite, Bezier };
inline constexpr EnumName<PatchForm> kPatchFormNames[] = {{"hermite", PatchForm::Hermite}, {"bezier", PatchForm::Bezier}};
std::string_view patchFormName(PatchForm f);

struct PatchSpec {
  std::string preset = "torus";              // torus | flat | saddle | zero-twist
  std::array<int, 2> splits{1, 1};           // patches along u and v (1..16)
  std::array<double, 4> domain{0, 1, 0, 1};  // U0, U1, V0, V1 (uniform knots)
  PatchForm form = PatchForm::Hermite;
  bool showError = true;       // colour by |X − torus| (torus preset only)
  bool showIsoLines = true;    // iso-parameter lines
  bool showHandles = true;
  int tessellation = 32;       // samples per patch edge (2..256)
  // The edited document: knot data (size (n+1)(m+1), row-major in u). Empty: from the preset.
  std::vector<KnotData> knots;
  bool operator==(const PatchSpec& o) const;
};

// The names of the presets, in menu order, and what each is.
const std::vector<std::pair<std::string, std::string>>& patchPresets();

// Knot vectors of the spec (uniform over the domain).
std::vector<double> patchKnotsU(const PatchSpec& spec);
std::vector<double> patchKnotsV(const PatchSpec& spec);
// The knot data: spec.knots when set, else generated from the preset. InputError for an unknown
// preset, splits outside 1..16 or an empty domain.
std::vector<KnotData> patchKnotData(const PatchSpec& spec);
PatchGrid buildPatchGrid(const PatchSpec& spec);

// A handle: which knot datum (Hermite) or which control point of which patch (Bézier).
struct PatchHandle {
  enum Kind { Point, TangentU, TangentV, Twist, Control } kind = Point;
  int a = 0, b = 0;          // Hermite: knot indices (u, v). Bézier: patch (i, j)
  int p = 0, q = 0;          // Bézier: control point indices in 0..3 (s, t)
};

// Every handle of the form with its position.
std::vector<std::pair<PatchHandle, Vec<3>>> patchHandles(const PatchSpec& spec);
Vec<3> patchHandlePosition(const PatchSpec& spec, const std::vector<KnotData>& knots, const PatchHandle& h);
// The spec with the handle moved to `position` (knot data written into spec.knots).
PatchSpec movePatchHandle(const PatchSpec& spec, const PatchHandle& h, const Vec<3>& position);

// Bézier control points of patch (i, j) from the knot data: [p][q] = b_pq.
std::array<std::array<Vec<3>, 4>, 4> patchControlPoints(const PatchSpec& spec, const std::vector<KnotData>& knots,
                                                        int i, int j);

}  // namespace hermite
