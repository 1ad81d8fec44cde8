#pragma once
// Triangle mesh files: read OFF, OBJ, PLY (ascii, binary little/big endian),
// glTF / GLB; write GLB / glTF, PLY (binary), OBJ. The format is chosen by the extension.
// Every malformed input is an InputError naming the file and what was wrong; saving never
// destroys an existing file (temporary + rename, atomic_file.h) and an unwritable path is an
// EnvironmentError.

#include <string>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// The extension of `path` in lower case, with its dot (".ply" for "Scan.PLY"; "" when none):
// what picks the format of mesh, point and output files.
std::string lowercaseExtension(const std::string& path);

// A triangle mesh (at least one triangle; InputError otherwise, e.g. for a point set).
TriMesh loadMesh(const std::string& path);
// Writes .glb, .gltf (buffers embedded), .ply (binary little endian) or .obj. InputError for
// another extension or a mesh that breaks TriMesh's promises (index out of range, NaN).
void saveMesh(const std::string& path, const TriMesh& mesh);

// True for the extensions loadMesh reads (.off .obj .ply .gltf .glb, any case).
bool isMeshFileExtension(const std::string& path);

// Like loadMesh but a file without faces is fine: a point set (PLY without a face element, OBJ
// `v` + `vn` lines only, glTF POINTS) gives a mesh with no triangles. Used by the point loaders.
// A zero normal in the file stays a zero column of `normals` (the point loaders estimate it).
TriMesh loadMeshFile(const std::string& path);

}  // namespace hermite
