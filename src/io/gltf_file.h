#pragma once
// glTF 2.0 (.gltf JSON with embedded or external buffers, .glb binary) through tinygltf, with
// the checks tinygltf leaves to its caller: accessor counts, component types and element types,
// bufferView / byteOffset / byteStride ranges inside their buffers, index ranges and finite
// coordinates. Read: every mesh primitive reachable from the default scene (all meshes when
// there is no scene), node transforms applied; TRIANGLES (mode 4) give triangles, POINTS
// (mode 0) give vertices only (an oriented point set with NORMAL). Write: one mesh, one node.

#include <string>
#include <string_view>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// Parses a glTF or GLB file held in memory (GLB when it starts with the "glTF" magic); `path`
// names it in every InputError and gives the directory external buffers are read from.
TriMesh readGltf(std::string_view bytes, const std::string& path);

// The bytes of `mesh` as GLB (`binary`) or as glTF JSON with the buffer embedded as a data URI.
// `path` is only used in error messages.
std::string writeGltf(const TriMesh& mesh, bool binary, const std::string& path);

}  // namespace hermite
