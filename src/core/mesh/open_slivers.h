#pragma once
// Open slivers: pieces of a contour that have a boundary and less area than one grid cell's face
// (docs/maths.md, Contouring). Where a field's zero set only grazes a few grid points — the
// overshoot of a fit beside a sharp edge, cut open where the field has no data — marching cubes
// makes a piece of a few triangles whose vertices sit within the 10⁻³ clamp of the points: below
// the grid's resolution, away from the surface (CGAL's anchor and rotor at 256³: 3–4 triangles,
// 0.7–1.3 % of the diagonal from the true surface, areas 0.003 and 0.04 of a cell face). Closed
// pieces are kept whatever their size.

#include "core/base/implicit_field.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// Removes the triangles of every open component whose area is below maxArea, then the vertices
// no triangle uses, unless the mesh is a single component. Returns how many components were removed.
int dropOpenSlivers(TriMesh& mesh, double maxArea);

// The open slivers of a contour of `field` on a grid of cells `h`: dropOpenSlivers with the
// smallest face of a cell as the bound, where the field has no-data regions (only there can a
// piece be cut open) and the contour is in pieces (found first by the cheap vertex union-find).
int dropGridSlivers(TriMesh& mesh, const ImplicitField<3>& field, const Vec<3>& h);

}  // namespace hermite
