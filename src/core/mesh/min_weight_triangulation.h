#pragma once
// Hole filling's fallback first patch (hole_fill.h, stage 2 when the advancing front fails): the
// minimum-weight triangulation of the hole's boundary polygon, then refined to the surrounding
// edge length (docs/maths.md, Hole filling).

#include <functional>

#include "core/mesh/hole_patch.h"
#include "core/mesh/prepared_mesh.h"

namespace hermite {

// Triangulates the loop with no new vertices by dynamic programming over its sub-polygons. The
// weight of a triangulation compares, in this order: the number of triangles with an angle below
// 1°, the largest dihedral angle between neighbouring triangles (the mesh's own triangles along
// the boundary included), the total area. A polygon of more than maxDirect vertices is first cut
// along short chords (the shortest relative to the boundary path it bridges) into pieces of at
// most maxDirect vertices, each solved exactly: O(n²) per cut, O(maxDirect³) per piece.
// Triangles are 3 × T vertex ids of the mesh, oriented like the mesh across the boundary;
// `maxDihedral` (optional) receives the triangulation's largest dihedral angle, radians.
// `keepGoing` (optional) is asked every 64 chord rows and before each piece; false from it stops
// with no triangles.
Eigen::Matrix3Xi minWeightTriangulation(const PreparedMesh& prepared, const BoundaryLoop& loop, int maxDirect = 96,
                                        double* maxDihedral = nullptr, const std::function<bool()>& keepGoing = {});

// A triangulation whose median angle with the mesh across the boundary edges exceeds this folds
// back onto the mesh. When its triangles also lie on the mesh (90 % of their centroids within
// kSheetGap × the hole's diameter of it) the loop is the rim of an open surface (the
// "hole" is everything outside it), not a hole to close; otherwise it closes a thin wedge, such as
// a blade whose upper face is missing.
inline constexpr double kRimDihedral = 150.0 * 3.14159265358979323846 / 180.0;
inline constexpr double kSheetGap = 0.02;

// The median, over the loop's edges, of the angle between the mesh triangle and the triangle of
// `triangles` on either side of the edge (radians; π when an edge is not covered).
double medianBoundaryDihedral(const PreparedMesh& prepared, const BoundaryLoop& loop, const Eigen::Matrix3Xi& triangles);

// A patch that would need more than this many triangles of the boundary's edge length is refined
// with graded sizes (patch_refinement.h, grading kPatchGrading): a round 2 000-edge hole would
// otherwise take about 700 000 triangles, with fairing and projection to match.
inline constexpr double kUniformPatchTriangles = 20000;
inline constexpr double kPatchGrading = 0.25;

// The fallback patch: minWeightTriangulation (refused, `closed` false, when it is the rim of an
// open surface: see kRimDihedral), then edges longer than 4/3 of the boundary's mean edge length
// (graded for large holes, see above) split at their midpoints and interior edges flipped where
// that raises the smaller minimum angle of the two triangles, until no edge is too long. `progress` (optional) is called
// with a fraction in [0, 1]; returning false stops with `closed` false.
HolePatch minWeightPatch(const PreparedMesh& prepared, const BoundaryLoop& loop,
                         const std::function<bool(double)>& progress = {});

}  // namespace hermite
