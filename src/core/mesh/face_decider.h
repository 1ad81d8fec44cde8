#pragma once
// Ambiguous faces of marching cubes decided by f itself (docs/maths.md, Contouring).
//
// A cube face whose diagonal corners share a sign (two inside, two outside, crosswise) has two
// ways to join its four crossings. The asymptotic decider reads the sign of the bilinear
// interpolant of the four corner values at its saddle point; where f is far from bilinear over
// the face — a part about a cell thick — it joins what f separates. On the Stanford dragon's
// 200 000-sample mesh at 256³ three outside corners of one cell, each cut off by f alone, were
// joined across two faces whose middles f has inside: one nine-sided polygon around a horn, its
// centre vertex on the horn's axis a sample spacing from the surface. Here each ambiguous face of
// the cells that make geometry gets the sign of f at that same saddle point instead (one batch of
// evaluations; few faces are ambiguous). The point depends only on the face's corner values and
// grid lines, so the two cells that share a face decide it alike, and the contour stays closed
// and manifold.

#include <cstdint>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"
#include "core/mesh/marching_grid.h"

namespace hermite::detail {

// Decisions for ambiguous faces, keyed by the face's lowest grid point and normal axis
// (key = 3 · point index + axis, the grid's own indexing), sorted.
struct FaceDecisions {
  std::vector<std::int64_t> keys;
  std::vector<signed char> outsideConnected;  // 1: the outside corners join across the face; −1: undecided
  // The decision for a face, or −1 when it has none (not ambiguous, or f not finite there).
  int lookup(std::int64_t key) const;
};

// Whether the face (key as above) has its diagonal corners sharing a sign, crosswise.
bool ambiguousFace(const MarchingGrid<3>& g, std::int64_t key);

// The ambiguous faces of `cells` (cube origins, grid point indices), decided by the sign of f at
// the bilinear interpolant's saddle point of each (f ≥ 0: the outside corners join).
FaceDecisions decideAmbiguousFaces(const MarchingGrid<3>& g, const ImplicitField<3>& field,
                                   const std::vector<std::int64_t>& cells, const CancelToken* cancel);

}  // namespace hermite::detail
