#pragma once
// Closed parametric meshes and hole cutting: the built-in holed meshes of the hole-filling mode,
// the hole-filling bench and the mesh tests all start from these.

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// The torus ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) on an nu × nv grid,
// counter-clockwise from outside (∂u × ∂v points outward).
TriMesh parametricTorusMesh(int nu, int nv, double R = 0.7, double r = 0.3);

// The unit sphere on nu longitudes × (nv − 1) latitude rings plus the two poles,
// counter-clockwise from outside.
TriMesh uvSphereMesh(int nu, int nv);

// The mesh without every triangle that has a vertex within `radius` of `centre`: one hole per
// ball (vertices are kept, ids unchanged).
TriMesh cutBall(const TriMesh& mesh, const Vec<3>& centre, double radius);

}  // namespace hermite
