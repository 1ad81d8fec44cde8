#pragma once
// Stage 2 of hole filling (hole_fill.h): the first patch over a hole.

#include "core/mesh/hole_fill_options.h"
#include "core/mesh/hole_patch.h"
#include "core/mesh/prepared_mesh.h"

namespace hermite {

// 2. The minimum-angle advancing front. Angles are in [0, 2π), measured on the hole's side about
// the local surface normal; < 75°: one triangle; 75°–135°: one new vertex at distance l along the
// bisector, two triangles; > 135°: two new vertices at thirds of the angle, three triangles.
// Safeguards that keep it from folding: a new vertex within mergeDistance·l of another front
// vertex is replaced by that vertex (the front splits in two, each closed in turn); a step whose
// new edges would repeat an edge or cross the front (in the vertex's tangent plane) is not taken
// (the next smallest angle is tried); fronts of ≤ clipFrontSize vertices are closed by clipping.
// Bounded: at most frontStepFactor · (n²/4 + 40n) + 10 steps, and a front that grows past 2n + 10 vertices
// (or n²/4 + 4n new ones) has folded — both end with `closed` false and the reason in `failure`.
HolePatch advancingFront(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options = {});

}  // namespace hermite
