#pragma once
// Chord refinement of a contoured mesh (docs/maths.md, Contouring; `mesh --chord-tolerance`).
//
// Marching cubes puts every vertex on f = 0, but a triangle is a chord of the curved zero set:
// between its corners it strays by about κL²/8 (κ the normal curvature along an edge of length
// L), which at a 256³ grid is 5 times the field's own error on scanned data (docs/performance.md,
// Real data). Each edge's stray is estimated from its end normals n₀, n₁ (unit ∇f) by the
// Hermite sagitta
//
//   s = (n₁ − n₀)·(p₁ − p₀) / 8        (> 0 where the surface bulges outward of the chord)
//
// and an edge is split when |s| > tolerance, or when its end normals differ by more than 60°
// (there the estimate means nothing). The new vertex starts at the sagitta's prediction
// (p₀ + p₁)/2 + s·n̄ (n̄ the normalised n₀ + n₁) and is projected onto f = 0 by Newton steps
// along ∇f, x ← x − f ∇f/‖∇f‖²; an edge whose projection fails (no data, a vanishing gradient, a
// step beyond half the edge from the chord's midpoint, not converged) stays whole, and so does an
// edge whose projected vertex `rejects` (a zero set that strayed from the samples between the grid's
// vertices: stray_pockets.h, StrayTest). A triangle with 1, 2 or 3 split edges becomes 2, 3 or 4
// triangles of the same orientation; both triangles of an edge see the same split, so a closed
// manifold mesh stays closed and manifold.

#include <functional>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

struct ChordRefinementOptions {
  double tolerance = 0.0;  // > 0, world units: edges whose estimated stray exceeds it are split
  int newtonSteps = 3;     // projection steps onto f = 0 per new vertex
  const CancelToken* cancel = nullptr;  // polled between batches of evaluations; throws Cancelled
  // When set: per column of its argument (the projected new vertices, 3 × C), whether that
  // vertex's edge stays whole.
  std::function<std::vector<char>(const Points<3>&)> rejects;
};

struct ChordRefinementReport {
  int splitEdges = 0;      // new vertices
  int unsplitEdges = 0;    // edges chosen for a split whose projection failed or was rejected: left whole
  int rejectedEdges = 0;   // of those, the ones `rejects` left whole
  double maxAbsF = 0;      // max |f| over the projected new vertices
  double ms = 0;           // wall clock
};

// One pass of chord refinement. `mesh` needs unit vertex normals (marching cubes gives ∇f/‖∇f‖);
// without them it is returned unchanged. New vertices get ∇f/‖∇f‖ as their normal.
TriMesh refineChords(const TriMesh& mesh, const ImplicitField<3>& field, const ChordRefinementOptions& options,
                     ChordRefinementReport* report = nullptr);

}  // namespace hermite
