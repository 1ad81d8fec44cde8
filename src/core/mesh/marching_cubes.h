#pragma once
// Marching cubes: the zero set of a 3D field as a triangle mesh (marching_options.h explains the method).

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "core/mesh/marching_options.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// Marching cubes; the mesh carries ∇f normals. Errors as marchingSquares. With anchors the grid
// may be refined where a thin part split the mesh (MarchingOptions::anchors); for a field with
// no-data regions, open pieces smaller than a cell face are left out (open_slivers.h).
TriMesh marchingCubes(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options = {},
                      MarchingReport* report = nullptr);

}  // namespace hermite
