#pragma once
// Refinement of a hole patch whose triangles are too large for the surrounding mesh (the
// minimum-weight triangulation has no interior vertices): longest-edge splitting and
// angle-improving edge flips (docs/maths.md, Hole filling).

#include <functional>

#include "core/mesh/hole_patch.h"
#include "core/mesh/prepared_mesh.h"

namespace hermite {

// Splits interior patch edges longer than 4/3 · patch.meanEdgeLength at their midpoints (longest
// first) and flips interior edges where the two triangles' smaller minimum angle grows (never
// onto an edge that exists, never folding the pair), until no interior edge is too long. The
// hole's boundary edges are kept. New vertices are appended to patch.vertices (ids from
// patch.baseId) with normals averaged from their triangles. `progress` (optional) receives the
// fraction of the expected triangle count reached; false from it stops: returns false.
bool refinePatch(const PreparedMesh& prepared, HolePatch& patch, const std::function<bool(double)>& progress = {});

// Flips interior patch edges (as above) until none improves, at most `passes` sweeps; returns
// the number of flips.
int improvePatchAngles(const PreparedMesh& prepared, HolePatch& patch, int passes = 8);

}  // namespace hermite
