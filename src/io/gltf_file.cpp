#include "io/gltf_file.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <vector>

#include "core/base/errors.h"
#include "io/gltf_file_access.h"
#include "io/mesh_format_common.h"

namespace hermite {

namespace {

// Images are not needed for geometry: accept them without decoding.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

tinygltf::TinyGLTF makeLoader(GltfFileAccess& access) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skipImage, nullptr);
  access.install(loader);
  return loader;
}

// tinygltf copies "extras" and "extensions" with one recursive call per nesting level: deeper
// JSON than any glTF needs is refused before it is parsed.
constexpr int kMaxJsonNesting = 256;

void checkJsonNesting(std::string_view json, const std::string& path) {
  int depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        throw InputError(path + ": JSON nested more than " + std::to_string(kMaxJsonNesting) +
                         " levels deep (at byte " + std::to_string(i) + "), deeper than this reader supports");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

std::uint32_t le32(std::string_view bytes, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

// GLB container checks with messages that say which length is wrong (tinygltf checks too, tersely).
void checkGlbContainer(std::string_view bytes, const std::string& path) {
  if (bytes.size() < 20) throw InputError(path + ": truncated GLB: " + std::to_string(bytes.size()) + " bytes, the header alone needs 20");
  const std::uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
  const std::uint32_t jsonLength = le32(bytes, 12), jsonType = le32(bytes, 16);
  if (version != 2) throw InputError(path + ": GLB version " + std::to_string(version) + " is not supported (expected 2)");
  if (length > bytes.size())
    throw InputError(path + ": truncated GLB: the header says " + std::to_string(length) + " bytes, the file has " +
                     std::to_string(bytes.size()));
  if (jsonType != 0x4E4F534Au) throw InputError(path + ": the first GLB chunk is not JSON");
  if (jsonLength == 0 || std::uint64_t{jsonLength} + 20 > length)
    throw InputError(path + ": the GLB JSON chunk length " + std::to_string(jsonLength) + " does not fit in the " +
                     std::to_string(length) + "-byte file");
}

// ---- accessors ------------------------------------------------------------------------------

// A checked view of an accessor's elements inside its buffer.
struct AccessorData {
  const unsigned char* first = nullptr;  // element 0
  std::size_t count = 0;
  std::size_t stride = 0;  // bytes between consecutive elements
  int componentType = 0;
};

std::string accessorName(int index, const std::string& role) {
  return "accessor " + std::to_string(index) + " (" + role + ")";
}

std::size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

// Everything tinygltf leaves unchecked: the accessor and bufferView indices, the element type
// and component type `role` needs, and that count elements of that size at that stride lie
// inside the bufferView, which lies inside its buffer.
AccessorData checkedAccessor(const tinygltf::Model& model, int index, const std::string& role, int type,
                             bool indices, const std::string& path) {
  const std::string name = accessorName(index, role);
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    throw InputError(path + ": " + name + " does not exist (there are " + std::to_string(model.accessors.size()) +
                     " accessors)");
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse) throw InputError(path + ": " + name + " is sparse, which this reader does not support");
  if (a.type != type) {
    const char* actual = a.type == TINYGLTF_TYPE_SCALAR ? "SCALAR"
                         : a.type == TINYGLTF_TYPE_VEC2 ? "VEC2"
                         : a.type == TINYGLTF_TYPE_VEC3 ? "VEC3"
                         : a.type == TINYGLTF_TYPE_VEC4 ? "VEC4"
                                                        : "a matrix type";
    throw InputError(path + ": " + name + " has type " + actual + ", expected " +
                     (type == TINYGLTF_TYPE_VEC3 ? "VEC3" : "SCALAR"));
  }
  const bool typeOk = indices ? (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                 a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                                 a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                              : a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (!typeOk)
    throw InputError(path + ": " + name + " has componentType " + std::to_string(a.componentType) + ", expected " +
                     (indices ? "5121, 5123 or 5125 (unsigned byte, short or int)" : "5126 (float)"));
  if (a.count == 0) throw InputError(path + ": " + name + " has count 0");
  if (a.count > static_cast<std::size_t>(kMaxMeshElements))
    throw InputError(path + ": " + name + " has count " + std::to_string(a.count) + ", more than this reader supports");
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
    throw InputError(path + ": " + name + " refers to bufferView " + std::to_string(a.bufferView) + ", but there are " +
                     std::to_string(model.bufferViews.size()));
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const std::string viewName = "bufferView " + std::to_string(a.bufferView);
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    throw InputError(path + ": " + viewName + " refers to buffer " + std::to_string(view.buffer) + ", but there are " +
                     std::to_string(model.buffers.size()));
  const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    throw InputError(path + ": " + viewName + " (byteOffset " + std::to_string(view.byteOffset) + ", byteLength " +
                     std::to_string(view.byteLength) + ") reaches past the end of buffer " +
                     std::to_string(view.buffer) + " (" + std::to_string(buffer.size()) + " bytes)");
  const std::size_t elementSize = componentSize(a.componentType) * (type == TINYGLTF_TYPE_VEC3 ? 3 : 1);
  const std::size_t stride = view.byteStride == 0 ? elementSize : view.byteStride;
  if (stride < elementSize)
    throw InputError(path + ": " + viewName + " has byteStride " + std::to_string(stride) + ", smaller than the " +
                     std::to_string(elementSize) + "-byte elements of " + name);
  // offset + (count − 1)·stride + elementSize ≤ byteLength, without overflow.
  const std::size_t length = view.byteLength;
  const bool fits = a.byteOffset <= length && elementSize <= length - a.byteOffset &&
                    (a.count - 1) <= (length - a.byteOffset - elementSize) / stride;
  if (!fits)
    throw InputError(path + ": " + name + " (" + std::to_string(a.count) + " elements of " +
                     std::to_string(elementSize) + " bytes, stride " + std::to_string(stride) + ", byteOffset " +
                     std::to_string(a.byteOffset) + ") does not fit in " + viewName + " (" + std::to_string(length) +
                     " bytes)");
  AccessorData data;
  data.first = buffer.data() + view.byteOffset + a.byteOffset;
  data.count = a.count;
  data.stride = stride;
  data.componentType = a.componentType;
  return data;
}

Eigen::Vector3d readVec3(const AccessorData& d, std::size_t i) {
  float v[3];
  std::memcpy(v, d.first + i * d.stride, sizeof(v));
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

std::uint32_t readIndex(const AccessorData& d, std::size_t i) {
  const unsigned char* p = d.first + i * d.stride;
  switch (d.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// ---- scene traversal --------------------------------------------------------------------------

Eigen::Affine3d nodeTransform(const tinygltf::Node& node, int index, const std::string& path) {
  const std::string name = "node " + std::to_string(index);
  auto finite = [&](const std::vector<double>& v, const char* what) {
    for (double x : v)
      if (!std::isfinite(x)) throw InputError(path + ": " + name + " has a non-finite " + what);
  };
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) throw InputError(path + ": " + name + ": matrix needs 16 numbers");
    finite(node.matrix, "matrix");
    t.matrix() = Eigen::Map<const Eigen::Matrix4d>(node.matrix.data());  // column-major, like glTF
    return t;
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) throw InputError(path + ": " + name + ": translation needs 3 numbers");
    finite(node.translation, "translation");
    t.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) throw InputError(path + ": " + name + ": rotation needs 4 numbers (x y z w)");
    finite(node.rotation, "rotation");
    Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (!(q.norm() > 0)) throw InputError(path + ": " + name + ": rotation is a zero quaternion");
    t.rotate(q.normalized());
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) throw InputError(path + ": " + name + ": scale needs 3 numbers");
    finite(node.scale, "scale");
    t.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  }
  return t;
}

struct Collected {
  std::vector<Eigen::Vector3d> vertices, normals;
  std::vector<int> corners;
  bool everyPrimitiveHasNormals = true;
};

// The primitive's mode (triangles when unset); throws for lines, which are not supported.
int checkedPrimitiveMode(const tinygltf::Primitive& primitive, const std::string& where, const std::string& path) {
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_POINTS && mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN)
    throw InputError(path + ": " + where + " has mode " + std::to_string(mode) +
                     " (lines), which is not supported; expected points (0) or triangles (4, 5, 6)");
  return mode;
}

// Appends the primitive's positions (and normals, if every vertex has one) in world space to
// out; returns how many vertices it has.
std::size_t addPrimitiveVertices(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                 const std::string& where, const Eigen::Affine3d& transform, const std::string& path,
                                 Collected& out) {
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) throw InputError(path + ": " + where + " has no POSITION attribute");
  const AccessorData positions = checkedAccessor(model, position->second, where + " POSITION", TINYGLTF_TYPE_VEC3, false, path);
  const auto normalAttribute = primitive.attributes.find("NORMAL");
  AccessorData normals;
  if (normalAttribute != primitive.attributes.end()) {
    normals = checkedAccessor(model, normalAttribute->second, where + " NORMAL", TINYGLTF_TYPE_VEC3, false, path);
    if (normals.count != positions.count)
      throw InputError(path + ": " + where + " has " + std::to_string(positions.count) + " positions but " +
                       std::to_string(normals.count) + " normals");
  } else {
    out.everyPrimitiveHasNormals = false;
  }
  if (out.vertices.size() + positions.count > static_cast<std::size_t>(kMaxMeshElements))
    throw InputError(path + ": more vertices than this reader supports");
  const Eigen::Matrix3d normalMatrix = transform.linear().inverse().transpose();
  for (std::size_t i = 0; i < positions.count; ++i) {
    out.vertices.push_back(transform * readVec3(positions, i));
    if (normals.count) out.normals.push_back(normalMatrix * readVec3(normals, i));
  }
  return positions.count;
}

// The primitive's corner list: its index accessor (each index checked against vertexCount), or
// 0, 1, 2, … without one.
std::vector<std::uint32_t> primitiveCorners(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                            std::size_t vertexCount, const std::string& where, const std::string& path) {
  std::vector<std::uint32_t> corner;
  if (primitive.indices >= 0) {
    const AccessorData indices = checkedAccessor(model, primitive.indices, where + " indices", TINYGLTF_TYPE_SCALAR, true, path);
    corner.resize(indices.count);
    for (std::size_t i = 0; i < indices.count; ++i) {
      corner[i] = readIndex(indices, i);
      if (corner[i] >= vertexCount)
        throw InputError(path + ": " + where + " index " + std::to_string(i) + " is " + std::to_string(corner[i]) +
                         ", but the primitive has " + std::to_string(vertexCount) + " vertices");
    }
  } else {
    corner.resize(vertexCount);
    for (std::size_t i = 0; i < corner.size(); ++i) corner[i] = static_cast<std::uint32_t>(i);
  }
  return corner;
}

// Appends the triangles of a triangle list, strip or fan over the corners to out.corners, the
// primitive's vertices starting at out.vertices[base].
void addTriangles(int mode, const std::vector<std::uint32_t>& corner, std::size_t base, const std::string& where,
                  const std::string& path, Collected& out) {
  auto triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    out.corners.insert(out.corners.end(), {static_cast<int>(base + a), static_cast<int>(base + b), static_cast<int>(base + c)});
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (corner.size() % 3 != 0)
      throw InputError(path + ": " + where + " has " + std::to_string(corner.size()) +
                       " triangle corners, not a multiple of 3");
    for (std::size_t i = 0; i + 2 < corner.size(); i += 3) triangle(corner[i], corner[i + 1], corner[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // glTF 2.0 §3.7.2.1: triangle i is (v_i, v_{i+1+i%2}, v_{i+2-i%2}), keeping one winding.
    for (std::size_t i = 0; i + 2 < corner.size(); ++i)
      triangle(corner[i], corner[i + 1 + i % 2], corner[i + 2 - i % 2]);
  } else {
    for (std::size_t i = 1; i + 1 < corner.size(); ++i) triangle(corner[0], corner[i], corner[i + 1]);
  }
}

// Appends one mesh primitive, in world space, to out.
void addPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                  const Eigen::Affine3d& transform, const std::string& path, Collected& out) {
  const int mode = checkedPrimitiveMode(primitive, where, path);
  const std::size_t base = out.vertices.size();
  const std::size_t vertexCount = addPrimitiveVertices(model, primitive, where, transform, path, out);
  if (mode == TINYGLTF_MODE_POINTS) return;
  addTriangles(mode, primitiveCorners(model, primitive, vertexCount, where, path), base, where, path, out);
}

void addMesh(const tinygltf::Model& model, int meshIndex, const Eigen::Affine3d& transform, const std::string& path,
             Collected& out) {
  if (meshIndex < 0 || static_cast<std::size_t>(meshIndex) >= model.meshes.size())
    throw InputError(path + ": mesh " + std::to_string(meshIndex) + " does not exist (there are " +
                     std::to_string(model.meshes.size()) + " meshes)");
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(meshIndex)];
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
    addPrimitive(model, mesh.primitives[p], "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p),
                 transform, path, out);
}

// Deepest node tree read; the walk is iterative, so this only bounds the work per root.
constexpr std::size_t kMaxNodeDepth = 100'000;

[[noreturn]] void throwMissingNode(int index, const tinygltf::Model& model, const std::string& path) {
  throw InputError(path + ": node " + std::to_string(index) + " does not exist (there are " +
                   std::to_string(model.nodes.size()) + " nodes)");
}

// Depth-first over the node tree below `root` with an explicit stack (a chain of nodes may be
// as deep as the file is long); each node may be reached once (glTF nodes form disjoint trees),
// which also stops cycles.
void addNodeTree(const tinygltf::Model& model, int root, std::vector<char>& visited, const std::string& path,
                 Collected& out) {
  struct Pending {
    int index;
    std::size_t depth;
    Eigen::Affine3d parent;
  };
  std::vector<Pending> stack{{root, 1, Eigen::Affine3d::Identity()}};
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    if (p.index < 0 || static_cast<std::size_t>(p.index) >= model.nodes.size()) throwMissingNode(p.index, model, path);
    if (visited[static_cast<std::size_t>(p.index)])
      throw InputError(path + ": node " + std::to_string(p.index) +
                       " is reached twice (a cycle or a shared child; glTF nodes must form trees)");
    if (p.depth > kMaxNodeDepth)
      throw InputError(path + ": node " + std::to_string(p.index) + " is " + std::to_string(p.depth) +
                       " levels deep in the node tree, more than this reader supports (" +
                       std::to_string(kMaxNodeDepth) + ")");
    visited[static_cast<std::size_t>(p.index)] = 1;
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(p.index)];
    const Eigen::Affine3d transform = p.parent * nodeTransform(node, p.index, path);
    if (node.mesh >= 0) addMesh(model, node.mesh, transform, path, out);
    // Reversed, so children come off the stack in file order (the vertex order of before).
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
      stack.push_back({*child, p.depth + 1, transform});
  }
}

// tinygltf's errors on one line, at most 400 bytes of them (they may quote a URI).
[[noreturn]] void throwLoadError(std::string err, bool binary, const std::string& path) {
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  for (char& c : err)
    if (c == '\n') c = ';';
  if (err.empty()) err = "unknown error";
  if (err.size() > 400) err = err.substr(0, 400) + "… (" + std::to_string(err.size()) + " bytes)";
  throw InputError(path + ": not a valid " + (binary ? "GLB" : "glTF") + " file (" + err + ")");
}

}  // namespace

TriMesh readGltf(std::string_view bytes, const std::string& path) {
  const bool binary = bytes.substr(0, 4) == "glTF";
  if (binary)
    checkGlbContainer(bytes, path);
  else
    requireSingleByteText(bytes, path, "glTF files");
  if (bytes.size() > std::numeric_limits<unsigned int>::max())
    throw InputError(path + ": larger than 4 GiB, which tinygltf cannot read");
  checkJsonNesting(binary ? bytes.substr(20, le32(bytes, 12)) : bytes, path);

  GltfFileAccess access(path);
  tinygltf::TinyGLTF loader = makeLoader(access);
  tinygltf::Model model;
  std::string err, warn;
  const std::string& baseDir = GltfFileAccess::baseDirectory();
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                           static_cast<unsigned int>(bytes.size()), baseDir)
             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                          baseDir);
  access.throwIfFailed();
  if (!ok) throwLoadError(err, binary, path);

  // Extensions that change how geometry is stored; the others (materials, textures, lights)
  // do not matter for the vertices and triangles read here.
  for (const std::string& required : model.extensionsRequired)
    if (required == "KHR_draco_mesh_compression" || required == "EXT_meshopt_compression" ||
        required == "KHR_mesh_quantization")
      throw InputError(path + ": requires the glTF extension " + required + ", which this reader does not support");

  Collected out;
  int scene = model.defaultScene;
  if (scene < 0 && !model.scenes.empty()) scene = 0;
  if (scene >= static_cast<int>(model.scenes.size()))
    throw InputError(path + ": the default scene " + std::to_string(scene) + " does not exist");
  if (scene >= 0) {
    std::vector<char> visited(model.nodes.size(), 0);
    for (int root : model.scenes[static_cast<std::size_t>(scene)].nodes)
      addNodeTree(model, root, visited, path, out);
  } else {
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
      addMesh(model, static_cast<int>(m), Eigen::Affine3d::Identity(), path, out);
  }
  if (out.vertices.empty()) throw InputError(path + ": no mesh primitives with vertices");

  TriMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(out.vertices.size()));
  for (std::size_t i = 0; i < out.vertices.size(); ++i) mesh.vertices.col(static_cast<Eigen::Index>(i)) = out.vertices[i];
  if (out.everyPrimitiveHasNormals) {
    mesh.normals.resize(3, static_cast<Eigen::Index>(out.normals.size()));
    for (std::size_t i = 0; i < out.normals.size(); ++i) mesh.normals.col(static_cast<Eigen::Index>(i)) = out.normals[i];
  }
  mesh.triangles =
      Eigen::Map<const Eigen::Matrix3Xi>(out.corners.data(), 3, static_cast<Eigen::Index>(out.corners.size() / 3));
  checkAndNormalizeMesh(mesh, path, ZeroNormals::Keep);
  return mesh;
}

namespace {

// One buffer holding the positions, then the normals when the mesh has them, then the triangle
// indices: float32 × 3 per vertex, uint32 × 3 per triangle.
tinygltf::Buffer meshBuffer(const TriMesh& mesh) {
  const std::size_t vec3Bytes = static_cast<std::size_t>(mesh.vertexCount()) * 3 * sizeof(float);
  const std::size_t indexBytes = static_cast<std::size_t>(mesh.triangleCount()) * 3 * sizeof(std::uint32_t);
  const bool normals = mesh.hasNormals();
  tinygltf::Buffer buffer;
  buffer.data.resize(vec3Bytes * (normals ? 2 : 1) + indexBytes);
  unsigned char* p = buffer.data.data();
  const Eigen::Matrix3Xf positions = mesh.vertices.cast<float>();
  std::memcpy(p, positions.data(), vec3Bytes);
  if (normals) {
    const Eigen::Matrix3Xf n = mesh.normals.cast<float>();
    std::memcpy(p + vec3Bytes, n.data(), vec3Bytes);
  }
  if (indexBytes > 0) {
    const Eigen::Matrix<std::uint32_t, 3, Eigen::Dynamic> t = mesh.triangles.cast<std::uint32_t>();
    std::memcpy(p + vec3Bytes * (normals ? 2 : 1), t.data(), indexBytes);
  }
  return buffer;
}

// Appends a view of buffer 0 and an accessor of it; the accessor's index.
int addAccessor(tinygltf::Model& model, std::size_t offset, std::size_t length, int target, int componentType,
                int type, std::size_t count) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  model.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  a.byteOffset = 0;
  a.componentType = componentType;
  a.type = type;
  a.count = count;
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size() - 1);
}

// The mesh's one primitive (triangles, or points when it has none) over meshBuffer's layout.
tinygltf::Primitive meshPrimitive(const TriMesh& mesh, tinygltf::Model& model) {
  const std::size_t vertexCount = static_cast<std::size_t>(mesh.vertexCount());
  const std::size_t vec3Bytes = vertexCount * 3 * sizeof(float);
  const std::size_t indexCount = static_cast<std::size_t>(mesh.triangleCount()) * 3;
  const bool normals = mesh.hasNormals();
  tinygltf::Primitive primitive;
  primitive.mode = indexCount > 0 ? TINYGLTF_MODE_TRIANGLES : TINYGLTF_MODE_POINTS;
  const int position = addAccessor(model, 0, vec3Bytes, TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                   TINYGLTF_TYPE_VEC3, vertexCount);
  // POSITION needs min and max (glTF 2.0 §5.1.1), of the stored floats: rounding to float is
  // monotone, so those are the rounded extremes of the doubles.
  const Eigen::Vector3f lo = mesh.vertices.rowwise().minCoeff().cast<float>();
  const Eigen::Vector3f hi = mesh.vertices.rowwise().maxCoeff().cast<float>();
  model.accessors[static_cast<std::size_t>(position)].minValues = {lo.x(), lo.y(), lo.z()};
  model.accessors[static_cast<std::size_t>(position)].maxValues = {hi.x(), hi.y(), hi.z()};
  primitive.attributes["POSITION"] = position;
  if (normals)
    primitive.attributes["NORMAL"] = addAccessor(model, vec3Bytes, vec3Bytes, TINYGLTF_TARGET_ARRAY_BUFFER,
                                                 TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, vertexCount);
  if (indexCount > 0)
    primitive.indices = addAccessor(model, vec3Bytes * (normals ? 2 : 1), indexCount * sizeof(std::uint32_t),
                                    TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                    TINYGLTF_TYPE_SCALAR, indexCount);
  return primitive;
}

}  // namespace

std::string writeGltf(const TriMesh& mesh, bool binary, const std::string& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Hermite Lab";
  tinygltf::Scene scene;
  if (mesh.vertexCount() > 0) {
    model.buffers.push_back(meshBuffer(mesh));
    tinygltf::Mesh gltfMesh;
    gltfMesh.primitives.push_back(meshPrimitive(mesh, model));
    model.meshes.push_back(gltfMesh);
    tinygltf::Node node;
    node.mesh = 0;
    model.nodes.push_back(node);
    scene.nodes.push_back(0);
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream stream;
  if (!writer.WriteGltfSceneToStream(&model, stream, !binary, binary))
    throw EnvironmentError(path + ": tinygltf could not serialise the mesh");
  return std::move(stream).str();
}

}  // namespace hermite
