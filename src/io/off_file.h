#pragma once
// Object File Format (Geomview OFF) reader: "OFF" / "COFF" / "NOFF" / "CNOFF" header line
// (optional), "V F [E]" counts, V vertex lines "x y z [nx ny nz (NOFF)] [colour]", F face lines
// "n i0 … i(n-1) [colour]" (0-based; polygons are fan-triangulated). '#' starts a comment.

#include <string>
#include <string_view>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// Parses an OFF file held in memory; `path` names it in every InputError.
TriMesh readOff(std::string_view bytes, const std::string& path);

}  // namespace hermite
