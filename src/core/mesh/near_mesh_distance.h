#pragma once
// Distances from a few points to a triangle mesh, within a reach: what the refined contouring
// pass reads to tell whether a grid's contour lies off the samples it missed (marching_cubes.cpp).

#include <vector>

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// For each column of `points`, the distance to the nearest triangle of `mesh` when it is below
// `reach` (> 0), else `reach`. Only the triangles within reach of some point are looked at, so
// the cost is one pass over the triangles plus the points' neighbourhoods.
std::vector<double> distancesToMeshWithin(const TriMesh& mesh, const Points<3>& points, double reach);

}  // namespace hermite
