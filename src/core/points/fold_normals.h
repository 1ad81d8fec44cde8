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
// levels (split at their widest gap, at least 3 points each) at least bandᵢ apart, and pᵢ lies 15 %
// or more of the way from each. Such a point (a rim's sample) takes the sheets' line in the sheet
// fit and sits within a band of both sheets: an edge "along a sheet" to it would join the two
// sheets in one patch, so the orientation does not trust it (orientNormals).
template <int Dim>
std::vector<char> betweenSheets(const Points<Dim>& P, const Points<Dim>& N, const NeighbourGraph& g,
                                const std::vector<double>& band);

// Re-estimates, after orientation, the normals of the points (`N`, Dim × N, unit, oriented) whose
// k neighbours hold two opposite-facing sheets, points with `fixed` set excepted. Per point i
// (neighbours j ≠ i, unit normals mⱼ):
//   1. two sheets: some pair of neighbours' normals lies more than 150° apart; e is the main axis
//      of Σ mⱼ mⱼᵀ; the neighbours within 30° of +e form sheet "+", those within 30° of −e sheet
//      "−", each of at least 2, their mean offsets h± = e·(pⱼ − pᵢ) at least bandᵢ apart (the
//      separation the sheet fit needs); otherwise i is left as it is.
//   2. where pᵢ lies between them: f = −h₋ / (h₊ − h₋), clamped to [0, 1] (0 on sheet "−", 1 on
//      "+"); its own sheet's normal is the mean normal of the nearer sheet, or i's own when that
//      lies within 30° of it (a sheet point keeps its estimate; a bad line or a sign error on a
//      sheet of a thin part takes its sheet's).
//   3. the fold: u, the direction from the sheets' centroid to pᵢ within the sheets' plane (⊥ e),
//      when that distance is at least `endFraction` × the neighbourhood radius (i at the end of
//      the sheets: a rim, not the middle of a thin part). The sheets face away from each other
//      (h₊ > h₋, a solid between them, the rim convex): the fold faces +u; else (a crack) −u.
//   4. the normal: normalize(w·(±u) + (1 − w)·sheet normal), w = clamp((min(f, 1 − f) − 0.05) / 0.2,
//      0, 1): the fold's direction between the sheets, the sheet's at them, a blend across the
//      crease lines.
// `band` holds the sheet bands (sheetBands), `sheetBand` the factor that made them (so that the
// neighbourhood radius is band / sheetBand). Returns how many normals changed.
template <int Dim>
int foldNormals(const Points<Dim>& P, Points<Dim>& N, const std::vector<char>& fixed, const NeighbourGraph& g,
                const std::vector<double>& band, double sheetBand);

}  // namespace hermite::detail
