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

// uvSphereMesh(nu, nv) without the triangles that touch its north pole or its first `openRings`
// latitude rings (one hole of nu boundary edges), every vertex then lifted by
// wave · (3x²y − y³) along z: a smooth surface whose hole rim is not planar.
TriMesh openWavySphereMesh(int nu, int nv, int openRings, double wave);

// parametricTorusMesh(nu, nv) with around × across holes cut by cutBall: centres on the
// surface spread over u (around) and v (across), every other row shifted by half a step; radii
// cycling through minRadius … maxRadius in a fixed order.
TriMesh holedTorusMesh(int nu, int nv, int around, int across, double minRadius, double maxRadius);

// The mesh without every triangle that has a vertex within `radius` of `centre`: one hole per
// ball (vertices are kept, ids unchanged).
TriMesh cutBall(const TriMesh& mesh, const Vec<3>& centre, double radius);

}  // namespace hermite
