#include "io/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "core/base/errors.h"
#include "io/atomic_file.h"
#include "io/gltf_file.h"
#include "io/mesh_format_common.h"
#include "io/obj_file.h"
#include "io/off_file.h"
#include "io/ply_file.h"

namespace hermite {

namespace {

constexpr const char* kReadable = ".off, .obj, .ply, .gltf, .glb";
constexpr const char* kWritable = ".glb, .gltf, .ply, .obj";

}  // namespace

std::string lowercaseExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool isMeshFileExtension(const std::string& path) {
  const std::string ext = lowercaseExtension(path);
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb";
}

TriMesh loadMeshFile(const std::string& path) {
  const std::string ext = lowercaseExtension(path);
  if (!isMeshFileExtension(path))
    throw InputError(path + ": unsupported mesh file extension '" + ext + "' (supported: " + kReadable + ")");
  if (ext == ".off") return readOff(readFileBytes(path, "OFF"), path);
  if (ext == ".obj") return readObj(readFileBytes(path, "OBJ"), path);
  if (ext == ".ply") return readPly(readFileBytes(path, "PLY"), path);
  return readGltf(readFileBytes(path, ext == ".glb" ? "GLB" : "glTF"), path);
}

TriMesh loadMesh(const std::string& path) {
  TriMesh mesh = loadMeshFile(path);
  if (mesh.triangleCount() == 0)
    throw InputError(path + ": has " + std::to_string(mesh.vertexCount()) +
                     " vertices but no triangles (a point set, not a mesh)");
  return mesh;
}

void saveMesh(const std::string& path, const TriMesh& mesh) {
  const std::string ext = lowercaseExtension(path);
  if (ext != ".glb" && ext != ".gltf" && ext != ".ply" && ext != ".obj")
    throw InputError(path + ": cannot write mesh file extension '" + ext + "' (supported: " + kWritable + ")");
  // The writers trust the mesh: check it is what TriMesh promises before anything is written.
  if (mesh.triangles.cols() > 0 && mesh.vertices.cols() == 0)
    throw InputError(path + ": cannot save triangles without vertices");
  TriMesh checked = mesh;
  checkAndNormalizeMesh(checked, path, ZeroNormals::Reject);

  if (ext == ".glb" || ext == ".gltf")
    if (const auto beyond = firstBeyondFloatRange(checked.vertices)) {
      char value[32];
      std::snprintf(value, sizeof value, "%.9g", checked.vertices(beyond->second, beyond->first));
      throw InputError(path + ": vertex " + std::to_string(beyond->first) + " has the coordinate " + value +
                       ", beyond the 32-bit float range of glTF (about ±3.4e38); write .ply or .obj, which keep it");
    }
  std::string bytes;
  if (ext == ".obj")
    bytes = writeObj(checked);
  else if (ext == ".ply")
    bytes = writePly(checked);
  else
    bytes = writeGltf(checked, ext == ".glb", path);
  writeFileAtomically(path, bytes);
}

}  // namespace hermite
