#pragma once
// Distances from a few points to a triangle mesh, within a reach: what the refined contouring
// pass reads to tell whether a grid's contour lies off the samples it missed (marching_cubes.cpp).

#include <vector>

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// For each column of `points`, the distance to the nearest triangle of `mesh` when it is below
// `reach` (> 0), else `reach` (also for a point that is not finite). The triangles near the
// points' box are bucketed in a grid of at most 64 cubes along its longest side; a point reads its
// own cube. So the cost is one pass over the triangles plus the points' cubes.
std::vector<double> distancesToMeshWithin(const TriMesh& mesh, const Points<3>& points, double reach);

}  // namespace hermite
