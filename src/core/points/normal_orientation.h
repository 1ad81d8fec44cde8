#pragma once
// Orientation of estimated normal lines (docs/maths.md, "Normal estimation"): how an orientation
// crosses one neighbour edge, and the patch-vote propagation over the whole cloud.

#include <vector>

#include "core/base/geometry.h"
#include "core/points/neighbour_graph.h"
#include "core/points/normal_estimation.h"

namespace hermite::detail {

// How an orientation crosses the edge i → j, and at what cost (see the header). `flip` says
// whether nⱼ as it stands must change sign to follow nᵢ as it stands (i is the oriented end).
// With d = pⱼ − pᵢ, the offsets oᵢ = |d·n̂ᵢ|, oⱼ = |d·n̂ⱼ| against the sheet bands bᵢ, bⱼ say whether
// each end sees the other on its own sheet (o ≤ b) or off it:
//   along a sheet   both on one sheet, d in both tangent planes (within asin gapSine), normals
//                   agree: copy (flip when nᵢ·nⱼ < 0), cost 1 − |nᵢ·nⱼ| < 1;
//   across a gap    both off one another's sheet (or d along both normals, the old test kept for
//                   infinite bands), normals parallel, and the two sign rules below agree: the
//                   sheets of a closed surface face each other there, so nⱼ takes the opposite
//                   orientation, cost 2 + (1 − |nᵢ·nⱼ|) + (1 − the smaller |d̂·n|);
//   any other edge  (a crease, a fold, noise), the last resort at cost 4 + (1 − its margin):
//                   where d leaves both tangent planes more steeply than the normals agree
//                   (min |d̂·n| > |nᵢ·nⱼ|, a sharp crease) by the crease rule — across a crease
//                   of a consistently oriented surface, convex or concave, d·nᵢ and d·nⱼ have
//                   opposite signs — with margin min |d̂·n|; else copy, margin |nᵢ·nⱼ|.
// A neighbour on the other sheet a lateral distance away from pᵢ makes a shallow d (within 30° of
// both planes once the gap is under ~1.7 times that distance), which the angles alone took for
// an edge along a sheet, copying the orientation across the gap at cost < 1; the bands reject it.
// Along a sheet and across a gap need both ends `trusted` (agreesWithNeighbours); an edge to an
// outlier line is always the last resort. Infinite bands and zero second sheets give the
// angle-only rules (orientationDisagreement, which has no sheet models).
enum class EdgeKind { Along, Across, Crease, Other };

struct EdgeRule {
  double cost = 0;
  bool flip = false;
  EdgeKind kind = EdgeKind::Other;
};

template <int Dim>
EdgeRule edgeRule(const Points<Dim>& P, const Points<Dim>& N, int i, int j, const NormalEstimationOptions& o,
                  double bandI, double bandJ, const Vec<Dim>& secondI, const Vec<Dim>& secondJ,
                  bool trusted = true);

// Orients the normals of the points with `done[i]` == 0 (docs/maths.md): patches first
// (growPatches), then a maximum spanning tree of the patch graph by the size of the summed
// evidence between patches (patchVotes), from the patches of the points already done, then from
// seeds; each tree edge turns the child patch over when its evidence says so. One wrong edge (a
// bad normal, a rim a spacing wide between two sheets) no longer decides a whole sheet: two
// sheets of a thin part are tied by dozens of edges across the gap. Fragments (patches of fewer
// than maxPatch / 2 points: rims, creases, clumps of outlier lines, whose normals are least
// sure) pass their orientation on only when no whole patch or given normal reaches further.
// `part` (when given, N entries) receives each point's tree: −1 for the trees grown from the
// points already done, else the index of its seed in seeding order. The points with `untrusted`
// set (when given, N entries: estimated lines of samples between two sheets, betweenSheets) are
// not trusted, like the outlier lines.
template <int Dim>
void orientNormals(const Points<Dim>& P, Points<Dim>& N, std::vector<char> done, const NeighbourGraph& g,
                   const std::vector<double>& band, const Points<Dim>& second, const NormalEstimationOptions& o,
                   std::vector<int>* part = nullptr, const std::vector<char>* untrusted = nullptr);

// Per tree (`part`, from orientNormals), the sign that makes the oriented normals agree with
// the most given ones (`given`, same shape): turns the tree over when at most a third of its
// given signs agree with the propagation. Between a third and two thirds the given signs say
// nothing (unoriented data) and the seed's outward rule stands.
template <int Dim>
void followGivenMajority(Points<Dim>& N, const Points<Dim>& given, const std::vector<int>& part);

}  // namespace hermite::detail
