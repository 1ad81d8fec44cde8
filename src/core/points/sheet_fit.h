#pragma once
// The local sheet model behind estimated normals (docs/maths.md, "Normal estimation"): the sheet
// band of each point and a normal robust to a second sheet among its neighbours.

#include <vector>

#include "core/base/geometry.h"
#include "core/points/neighbour_graph.h"

namespace hermite::detail {

// The sheet band of each point: sheetBand × the distance to its k-th nearest neighbour (the
// neighbourhood radius). Neighbours farther than that from a point's tangent plane lie on
// another sheet (or across a crease); see sheetNormal and edgeRule.
template <int Dim>
std::vector<double> sheetBands(const Points<Dim>& points, const NeighbourGraph& g, double sheetBand);

// Point i's normal, robust to a second sheet among its neighbours (docs/maths.md): every
// hyperplane through Dim of the k neighbourhood points (pᵢ included; 120 for k = 10 in 3D) gives
// a candidate normal n, scored by its truncated squared residual Σ min(r², band²) over the k
// (MSAC: inliers count by how well they fit, every outlier costs band²), once as one sheet
// through pᵢ (r = h = n·(pⱼ − pᵢ)) and once as two parallel sheets, through pᵢ and at the mean
// offset c of the neighbours beyond the band on the side holding more of them (at least 2),
// r = min(|h|, |h − c|). A candidate spanned by the other sheet's points gives the second model
// its exact normal even when pᵢ's own sheet holds only 3 of the k. Two sheets are taken when
// they fit at least two neighbours' worth (2·band²) better than the best single sheet: on one
// sheet, flat or mildly curved, every neighbour already fits within the band and they cannot.
// The normal is the smallest eigenvector of the inliers' covariance, each sheet about its own
// mean (parallel sheets share their normal, so all inliers estimate it); `second` receives the
// second sheet's offset times that normal (zero for one sheet). Plain PCA over all k when fewer
// than Dim + 1 fit, and at once (no search) when PCA's hyperplane fits all k as one sheet (below).
template <int Dim>
Vec<Dim> sheetNormal(const Points<Dim>& points, const NeighbourGraph& g, int i, double band, Vec<Dim>& second);

}  // namespace hermite::detail
