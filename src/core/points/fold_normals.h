#pragma once
// Normals at the folds of thin parts (docs/maths.md, "Normal estimation", Folds): where two
// sheets of a closed surface lie closer than the neighbourhood, the strip that joins them (the
// rim of a slab, the end of a plate, the bottom of a crack) is only a spacing or two wide. Its
// samples lie between the sheets, and their k neighbours are the two sheets, so the sheet fit
// gives them the sheets' normal line where the true normal lies in the sheets' plane. After the
// orientation, the oriented normals of the two sheets say where the fold is and which way it
// faces; this pass gives the samples there the normal of the fold.

#include <vector>

#include "core/base/geometry.h"
#include "core/points/neighbour_graph.h"

namespace hermite::detail {

// Which points lie between two sheets of a thin part, from their normal lines alone (before any
// orientation; `N` Dim × N, any sign, `band` the sheet bands): among the lines of the ring around
// pᵢ (its neighbours and theirs) within 30° of their main axis e, the offsets e·(pⱼ − pᵢ) form two
// levels (split at their widest gap, at least 3 points each) whose medians lie at least bandᵢ
// apart, and pᵢ lies 15 % or more of the way from each. Looked at only where pᵢ's k neighbours
// leave the plane of its own line by bandᵢ or more. Such a point (a rim's sample) gets the
// sheets' line from the sheet fit and sits within a band of both sheets: an edge "along a sheet"
// to it would join the two sheets in one patch, so the orientation of estimated lines does not
// trust it (completeNormals → orientNormals).
template <int Dim>
std::vector<char> betweenSheets(const Points<Dim>& P, const Points<Dim>& N, const NeighbourGraph& g,
                                const std::vector<double>& band);

// Re-estimates, after orientation, the normals of the points (`N`, Dim × N, unit, oriented) whose
// neighbourhood holds two opposite-facing sheets, points with `fixed` set excepted. Per point i,
// over the ring around pᵢ (its k neighbours and theirs, pᵢ excluded; unit normals mⱼ), looked at
// only where two of its k neighbours' normals lie more than 150° apart or pᵢ's lies within 30° of
// fewer than half of them, and not where pᵢ lies on its sheet (3 of its neighbours within a tenth
// of bandᵢ of its tangent plane with normals within 30° of its own: f ≈ 0 below, nothing to change):
//   1. two sheets: e is the main axis of the lines (Σ mⱼ mⱼᵀ, refitted once to the lines within
//      30° of it); the normals within 30° of +e form sheet "+", those within 30° of −e sheet "−",
//      each of at least 3, the medians h± of their offsets e·(pⱼ − pᵢ) at least bandᵢ apart (the
//      separation the sheet fit needs); otherwise i is left as it is.
//   2. where pᵢ lies between them: f = −h₋ / (h₊ − h₋), clamped to [0, 1] (0 on sheet "−", 1 on
//      "+"); its sheet's normal is the mean normal of the nearer sheet, or i's own when that lies
//      within 30° of it (a sheet point keeps its estimate; a bad line or a sign error on a sheet
//      of a thin part takes its sheet's).
//   3. the fold: â, the direction from pᵢ to the sheets' centroid within the sheets' plane (⊥ e),
//      when that offset is at least 0.2 × the neighbourhood radius (pᵢ at the end of the sheets:
//      a rim, not the middle of a thin part). The sheets face away from each other (h₊ > h₋, a
//      solid between them, the rim convex): the rim faces −â; else (a slot, a crack) +â.
//   4. the normal: normalize(w·(∓â) + (1 − w)·sheet normal), w = clamp((min(f, 1 − f) − 0.05) / 0.2,
//      0, 1): the rim's direction between the sheets, the sheet's at them, a blend across the
//      crease lines.
// `band` holds the sheet bands (sheetBands), `sheetBand` the factor that made them (so that the
// neighbourhood radius is band / sheetBand). Returns how many normals changed.
template <int Dim>
int foldNormals(const Points<Dim>& P, Points<Dim>& N, const std::vector<char>& fixed, const NeighbourGraph& g,
                const std::vector<double>& band, double sheetBand);

}  // namespace hermite::detail
