#pragma once
// Marching cubes: the zero set of a 3D field as a triangle mesh (marching_options.h explains the method).

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "core/mesh/grid_lines.h"
#include "core/mesh/marching_options.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// Marching cubes; the mesh carries ∇f normals. Errors as marchingSquares. With anchors the grid
// may be refined where a thin part split the mesh (MarchingOptions::anchors), and the tips the
// final grid still cut off such a part are left out (cut_tips.h); for a field with no-data
// regions, open pieces smaller than a cell face are left out (open_slivers.h).
// `lines`, when given, receives the grid lines of the mesh returned (the refined ones when it was
// refined).
TriMesh marchingCubes(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options = {},
                      MarchingReport* report = nullptr, GridLines<3>* lines = nullptr);

// One pass over the cells of `lines` as marchingCubes makes it, with `h` its uniform grid's cell
// (the no-data margin and the field's grid form follow it): no anchors, no review, no slivers
// left out. A part of a grid contoured again (contour_patch.h) meets the rest of it exactly.
TriMesh marchingCubesPass(const ImplicitField<3>& field, const GridLines<3>& lines, const Vec<3>& h,
                          const MarchingOptions& options = {});

}  // namespace hermite
