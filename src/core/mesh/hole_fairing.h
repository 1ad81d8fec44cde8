#pragma once
// Stage 3 of hole filling (hole_fill.h): smoothing the patch with the boundary fixed.

#include "core/mesh/hole_patch.h"
#include "core/mesh/prepared_mesh.h"

namespace hermite {

// 3. Least-squares-mesh fairing (uniform Laplacian rows for the new vertices and the boundary
// vertices, boundary fixed; mean-value weights for graded patches), solved by a sparse Cholesky
// factorisation of the normal equations. A thin-wedge patch (HolePatch::rimFold) has rows for its
// new vertices only: a membrane that stays inside the convex hull of its rim.
// Returns the patch with moved vertices (unchanged when it has none). NumericalError if the solve fails.
HolePatch fairPatch(const PreparedMesh& prepared, const HolePatch& patch);

}  // namespace hermite
