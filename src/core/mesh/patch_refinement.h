#pragma once
// Refinement of a hole patch whose triangles are too large for the surrounding mesh (the
// minimum-weight triangulation has no interior vertices): longest-edge splitting and
// angle-improving edge flips, or for graded sizes centroid insertion with Delaunay flips and
// smoothing (docs/maths.md, Hole filling).

#include <functional>

#include "core/mesh/hole_patch.h"
#include "core/mesh/prepared_mesh.h"

namespace hermite {

// Grading 0: splits interior patch edges longer than 4/3 · patch.meanEdgeLength at their
// midpoints (longest first) and flips interior edges where the two triangles' smaller minimum
// angle grows (never onto an edge that exists, never folding the pair), until no interior edge
// is too long. Grading > 0: the target length is l + grading · d at distance d from the nearest
// boundary vertex (l = patch.meanEdgeLength), so the triangles of a large hole grow towards its
// middle (a round hole of n edges then needs O(n log n) triangles, not O(n²)); triangles are
// split at their centroids while those are far enough from their corners for the target there
// (Liepa 2003), with Delaunay flips and smoothing between rounds. The hole's boundary edges are
// kept. New vertices are appended to patch.vertices (ids from patch.baseId) with normals averaged
// from their triangles. `progress` (optional) receives the fraction of the expected triangle
// count reached; false from it stops: returns false.
bool refinePatch(const PreparedMesh& prepared, HolePatch& patch, const std::function<bool(double)>& progress = {},
                 double grading = 0);

// Flips interior patch edges (as above) and moves new vertices of triangles with an angle below
// 5° to the mean of their neighbours where that raises the smallest angle around them, until
// nothing changes, at most `passes` sweeps; returns the number of flips.
int improvePatchAngles(const PreparedMesh& prepared, HolePatch& patch, int passes = 8);

}  // namespace hermite
