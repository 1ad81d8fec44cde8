#pragma once
// Wavefront OBJ: read through tinyobjloader (double precision build) with our own checks of the
// numbers it would otherwise read as 0 (NaN, "inf", garbage, missing coordinates); write `v`,
// `vn` and `f` lines. Faces are fan-triangulated; `l`, `p`, texture coordinates and materials
// are ignored (no .mtl file is opened).
//
// Vertex normals: with faces, each vertex gets the normalised mean of the `vn` its face corners
// name (none when some corner names none); without faces, the i-th `vn` belongs to the i-th `v`
// (an oriented point set), so their counts must match.

#include <string>
#include <string_view>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// Parses an OBJ file held in memory; `path` names it in every InputError.
TriMesh readObj(std::string_view bytes, const std::string& path);

// The OBJ text of `mesh` (1-based indices, `f a//a b//b c//c` when it has normals).
std::string writeObj(const TriMesh& mesh);

}  // namespace hermite
