#pragma once
// Triangle mesh files (DESIGN.md §4, §7): read OFF, OBJ, PLY (ascii, binary little/big endian),
// glTF / GLB; write GLB / glTF, PLY (binary), OBJ. The format is chosen by the extension.
// Every malformed input is an InputError naming the file and what was wrong; saving never
// destroys an existing file (temporary + rename, atomic_file.h) and an unwritable path is an
// EnvironmentError.

#include <string>

#include "core/tri_mesh.h"

namespace hermite {

TriMesh loadMesh(const std::string& path);
void saveMesh(const std::string& path, const TriMesh& mesh);

}  // namespace hermite
