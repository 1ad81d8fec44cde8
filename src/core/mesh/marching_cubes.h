#pragma once
// Marching cubes: the zero set of a 3D field as a triangle mesh (marching_options.h explains the method).

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "core/mesh/marching_options.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// Marching cubes; the mesh carries ∇f normals. Errors as marchingSquares.
TriMesh marchingCubes(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options = {},
                      MarchingReport* report = nullptr);

}  // namespace hermite
