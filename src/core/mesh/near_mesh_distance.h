#pragma once
// Distances from a few points to a triangle mesh, within a reach: what the refined contouring
// pass reads to tell whether a grid's contour lies off the samples it missed (marching_cubes.cpp).

#include <vector>

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// For each column of `points`, the distance to the nearest triangle of `mesh` when it is below
// `reach` (> 0), else `reach` (also for a point that is not finite). Triangles are bucketed in
// cells of edge `reach`, only those near some point; a triangle spanning more than a few dozen
// cells is measured against every point instead. So the cost is one pass over the triangles plus
// the points' neighbourhoods (and points × large triangles).
std::vector<double> distancesToMeshWithin(const TriMesh& mesh, const Points<3>& points, double reach);

}  // namespace hermite
