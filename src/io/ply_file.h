#pragma once
// Stanford PLY, our own reader and writer (no PLY library is packaged for Debian).
// Read: ascii, binary_little_endian and binary_big_endian 1.0. Element `vertex` with scalar
// properties x y z [nx ny nz] of any type; element `face` with a list `vertex_indices` (or
// `vertex_index`) of any integer type, polygons fan-triangulated. Every other property and
// element is skipped by its declared type. The header's counts are checked against the file
// size before anything is allocated; a truncated body, an index out of range, a non-finite
// coordinate or an unknown type is an InputError naming the file and the element/row.
// Write: binary_little_endian, float x y z [nx ny nz], faces as `list uchar int vertex_indices`.

#include <string>
#include <string_view>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// Parses a PLY file held in memory; `path` names it in every InputError. A file without a
// `face` element gives a mesh with no triangles (a point set).
TriMesh readPly(std::string_view bytes, const std::string& path);

// The bytes of `mesh` as binary little-endian PLY: coordinates and normals as 32-bit floats, or
// all as 64-bit doubles when a coordinate lies beyond the float range.
std::string writePly(const TriMesh& mesh);

}  // namespace hermite
