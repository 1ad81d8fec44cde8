#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "support/temp_dir.h"
#include "core/base/errors.h"
#include "io/mesh_file.h"
#include "io/point_file.h"
#include "scene/scene_fit.h"

using hermite::InputError;
using hermite::TriMesh;
namespace fs = std::filesystem;

namespace {

const std::string kMeshes = std::string(HERMITE_FIXTURES) + "/meshes";

// Each test's own folder, named after this file's tests.
struct TempDir : hermite::testing::TempDir {
  TempDir() : hermite::testing::TempDir("hermite_mesh_io_test") {}
};

// A closed octahedron with outward counter-clockwise triangles and unit vertex normals, the
// vertices moved off the lattice so float round trips are visible in the tolerances.
TriMesh octahedron(bool withNormals) {
  TriMesh m;
  m.vertices.resize(3, 6);
  m.vertices << 1.1, -0.9, 0.05, 0.0, 0.0, 0.0,  //
      0.0, 0.0, 1.3, -0.7, 0.0, 0.0,              //
      0.1, 0.0, 0.0, 0.0, 1.25, -1.0 / 3;
  m.triangles.resize(3, 8);
  m.triangles << 0, 2, 1, 3, 2, 0, 3, 1,  //
      2, 1, 3, 0, 0, 3, 1, 2,             //
      4, 4, 4, 4, 5, 5, 5, 5;
  if (withNormals) m.normals = m.vertices.colwise().normalized();
  return m;
}

void checkSameMesh(const TriMesh& a, const TriMesh& b, double tolerance) {
  REQUIRE(a.vertexCount() == b.vertexCount());
  REQUIRE(a.triangleCount() == b.triangleCount());
  CHECK((a.vertices - b.vertices).cwiseAbs().maxCoeff() <= tolerance);
  CHECK(a.triangles == b.triangles);
  REQUIRE(a.hasNormals() == b.hasNormals());
  // Normals are normalised again on reading: a unit vector may move by an ulp.
  if (a.hasNormals()) CHECK((a.normals - b.normals).cwiseAbs().maxCoeff() <= std::max(tolerance, 1e-15));
}

// Little- or big-endian bytes of a value.
template <class T>
void put(std::string& out, T value, bool bigEndian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (bigEndian)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  out.append(raw, sizeof(T));
}

}  // namespace

TEST_CASE("mesh_io: OFF with comments, a quad and the counts on the keyword line") {
  TempDir dir;
  const std::string path = dir.write("quad.off",
                                     "# a unit square and a triangle\n"
                                     "OFF 5 2 0\n"
                                     "0 0 0\n1 0 0\n1 1 0\n0 1 0  # comment after a vertex\n"
                                     "\n"
                                     "0.5 0.5 1\n"
                                     "4 0 1 2 3 255 0 0\n"  // a colour after the indices
                                     "3 0 1 4\n");
  const TriMesh m = hermite::loadMesh(path);
  REQUIRE(m.vertexCount() == 5);
  REQUIRE(m.triangleCount() == 3);  // the quad fan-triangulated + the triangle
  CHECK(m.vertices.col(2) == Eigen::Vector3d(1, 1, 0));
  CHECK(m.triangles.col(0) == Eigen::Vector3i(0, 1, 2));
  CHECK(m.triangles.col(1) == Eigen::Vector3i(0, 2, 3));
  CHECK(m.triangles.col(2) == Eigen::Vector3i(0, 1, 4));
  CHECK(!m.hasNormals());

  // NOFF: a normal after each vertex (normalised on reading); an oriented point set without faces.
  const std::string noff = dir.write("points.off", "NOFF\n2 0 0\n0 0 0  0 0 3\n1 2 3  -1 0 0\n");
  const TriMesh points = hermite::loadMeshFile(noff);
  REQUIRE(points.hasNormals());
  CHECK(points.triangleCount() == 0);
  CHECK(points.vertices.col(1) == Eigen::Vector3d(1, 2, 3));
  CHECK(points.normals.col(0) == Eigen::Vector3d(0, 0, 1));
  CHECK(points.normals.col(1) == Eigen::Vector3d(-1, 0, 0));
}

TEST_CASE("mesh_io: the OFF fixture (a cube) is a closed mesh") {
  const TriMesh m = hermite::loadMesh(kMeshes + "/cube.off");
  CHECK(m.vertexCount() == 8);
  CHECK(m.triangleCount() == 12);
  // Closed: every directed edge appears once and its reverse once.
  std::vector<std::pair<int, int>> edges;
  for (int t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) edges.emplace_back(m.triangles(k, t), m.triangles((k + 1) % 3, t));
  for (const auto& [a, b] : edges) {
    CHECK(std::count(edges.begin(), edges.end(), std::make_pair(a, b)) == 1);
    CHECK(std::count(edges.begin(), edges.end(), std::make_pair(b, a)) == 1);
  }
}

TEST_CASE("mesh_io: OBJ polygons, relative indices, v/vt/vn corners and no mtl access") {
  TempDir dir;
  const std::string path = dir.write("poly.obj",
                                     "mtllib missing.mtl\n"
                                     "o square\n"
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\n"
                                     "vn 0 0 2\n"
                                     "usemtl nothing\n"
                                     "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                                     "l 1 3\n");
  TriMesh m = hermite::loadMesh(path);
  REQUIRE(m.vertexCount() == 4);
  REQUIRE(m.triangleCount() == 2);
  CHECK(m.triangles.col(0) == Eigen::Vector3i(0, 1, 2));
  CHECK(m.triangles.col(1) == Eigen::Vector3i(0, 2, 3));
  REQUIRE(m.hasNormals());
  CHECK(m.normals.col(3) == Eigen::Vector3d(0, 0, 1));  // normalised

  const std::string relative = dir.write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
  m = hermite::loadMesh(relative);
  CHECK(m.triangles.col(0) == Eigen::Vector3i(0, 1, 2));
  CHECK(!m.hasNormals());
}

TEST_CASE("mesh_io: OBJ, PLY, GLB and glTF round trips (exact for OBJ, float precision for the others)") {
  TempDir dir;
  for (const bool normals : {false, true}) {
    CAPTURE(normals);
    const TriMesh original = octahedron(normals);
    const std::string obj = dir.file(normals ? "n.obj" : "p.obj");
    hermite::saveMesh(obj, original);
    checkSameMesh(hermite::loadMesh(obj), original, 0.0);  // shortest round-trip decimal text

    const std::string ply = dir.file(normals ? "n.ply" : "p.ply");
    hermite::saveMesh(ply, original);
    checkSameMesh(hermite::loadMesh(ply), original, 1e-6);  // 32-bit floats: 2^-24 relative

    for (const char* ext : {".glb", ".gltf"}) {
      const std::string gltf = dir.file(std::string(normals ? "n" : "p") + ext);
      hermite::saveMesh(gltf, original);
      checkSameMesh(hermite::loadMesh(gltf), original, 1e-6);
    }
  }
  // Only the targets remain: the temporaries of the atomic writes were renamed.
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path)) ++files;
  CHECK(files == 8);
}

TEST_CASE("mesh_io: PLY ascii, binary little and big endian with extra properties of every type") {
  TempDir dir;
  const TriMesh expected = octahedron(true);
  // Vertex: an int8 before x, a double x, float y z, a ushort label, normals as doubles / floats.
  // Face: an int flags before the uint-count / ushort-index list, a list of floats after it.
  const std::string headerBody =
      "comment extra properties must be skipped by their declared sizes\n"
      "element vertex 6\n"
      "property char tag\nproperty double x\nproperty float y\nproperty float32 z\n"
      "property ushort label\nproperty double nx\nproperty float ny\nproperty float nz\n"
      "element face 8\n"
      "property int flags\nproperty list uint ushort vertex_indices\nproperty list uchar float texcoord\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
      "end_header\n";
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    CAPTURE(format);
    const bool big = std::string(format) == "binary_big_endian";
    std::string bytes = std::string("ply\nformat ") + format + " 1.0\n" + headerBody;
    if (std::string(format) == "ascii") {
      for (int i = 0; i < 6; ++i) {
        char line[512];
        std::snprintf(line, sizeof(line), "-7 %.17g %.9g %.9g 65535 %.17g %.9g %.9g\n", expected.vertices(0, i),
                      static_cast<double>(static_cast<float>(expected.vertices(1, i))),
                      static_cast<double>(static_cast<float>(expected.vertices(2, i))), expected.normals(0, i),
                      static_cast<double>(static_cast<float>(expected.normals(1, i))),
                      static_cast<double>(static_cast<float>(expected.normals(2, i))));
        bytes += line;
      }
      for (int t = 0; t < 8; ++t)
        bytes += "0 3 " + std::to_string(expected.triangles(0, t)) + " " + std::to_string(expected.triangles(1, t)) +
                 " " + std::to_string(expected.triangles(2, t)) + " 2 0.5 0.25\n";
      bytes += "0 1\n";
    } else {
      for (int i = 0; i < 6; ++i) {
        put<std::int8_t>(bytes, -7, big);
        put<double>(bytes, expected.vertices(0, i), big);
        put<float>(bytes, static_cast<float>(expected.vertices(1, i)), big);
        put<float>(bytes, static_cast<float>(expected.vertices(2, i)), big);
        put<std::uint16_t>(bytes, 65535, big);
        put<double>(bytes, expected.normals(0, i), big);
        put<float>(bytes, static_cast<float>(expected.normals(1, i)), big);
        put<float>(bytes, static_cast<float>(expected.normals(2, i)), big);
      }
      for (int t = 0; t < 8; ++t) {
        put<std::int32_t>(bytes, 0, big);
        put<std::uint32_t>(bytes, 3, big);
        for (int k = 0; k < 3; ++k) put<std::uint16_t>(bytes, static_cast<std::uint16_t>(expected.triangles(k, t)), big);
        put<std::uint8_t>(bytes, 2, big);
        put<float>(bytes, 0.5f, big);
        put<float>(bytes, 0.25f, big);
      }
      put<std::int32_t>(bytes, 0, big);
      put<std::int32_t>(bytes, 1, big);
    }
    const TriMesh m = hermite::loadMesh(dir.write(std::string(format) + ".ply", bytes));
    checkSameMesh(m, expected, 1e-6);
    CHECK(m.vertices(0, 2) == expected.vertices(0, 2));  // the double property kept all its bits
  }
}

TEST_CASE("mesh_io: saving never destroys an existing file, and bad meshes and extensions are refused") {
  TempDir dir;
  const std::string path = dir.write("keep.obj", "precious");
  TriMesh bad = octahedron(false);
  bad.triangles(1, 3) = 6;  // out of range
  CHECK_THROWS_WITH_AS(hermite::saveMesh(path, bad),
                       (path + ": triangle 3 refers to vertex 6, but there are 6 vertices").c_str(), InputError);
  bad = octahedron(false);
  bad.vertices(2, 5) = std::nan("");
  CHECK_THROWS_AS(hermite::saveMesh(path, bad), InputError);
  bad = octahedron(true);
  bad.normals.col(4).setZero();
  CHECK_THROWS_WITH_AS(hermite::saveMesh(path, bad), (path + ": the normal of vertex 4 is zero").c_str(), InputError);
  std::ifstream in(path);
  std::string contents((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(contents == "precious");

  CHECK_THROWS_WITH_AS(hermite::saveMesh(dir.file("a.stl"), octahedron(false)),
                       (dir.file("a.stl") + ": cannot write mesh file extension '.stl' (supported: .glb, .gltf, .ply, "
                                            ".obj)")
                           .c_str(),
                       InputError);
  CHECK_THROWS_AS(hermite::saveMesh(dir.file("missing/dir/a.ply"), octahedron(false)), hermite::EnvironmentError);
  CHECK_THROWS_WITH_AS(hermite::loadMesh(dir.file("a.stl")),
                       (dir.file("a.stl") + ": unsupported mesh file extension '.stl' (supported: .off, .obj, .ply, "
                                            ".gltf, .glb)")
                           .c_str(),
                       InputError);
}

TEST_CASE("mesh_io: a point set is not a mesh") {
  TempDir dir;
  const std::string path = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nvn 0 1 0\n");
  CHECK_THROWS_WITH_AS(hermite::loadMesh(path),
                       (path + ": has 2 vertices but no triangles (a point set, not a mesh)").c_str(), InputError);
  const TriMesh points = hermite::loadMeshFile(path);
  CHECK(points.vertexCount() == 2);
  REQUIRE(points.hasNormals());
  CHECK(points.normals.col(1) == Eigen::Vector3d(0, 1, 0));
}

TEST_CASE("mesh_io: oriented point sets from PLY and OBJ through the point loaders") {
  TempDir dir;
  TriMesh cloud = octahedron(true);
  cloud.triangles.resize(3, 0);
  const std::string ply = dir.file("cloud.ply");
  const std::string obj = dir.file("cloud.obj");
  hermite::saveMesh(ply, cloud);
  hermite::saveMesh(obj, cloud);
  for (const std::string& path : {ply, obj}) {
    CAPTURE(path);
    CHECK(hermite::pointFileDimension(path) == 3);
    std::vector<std::string> warnings;
    const auto samples = hermite::loadPointFile3d(path, warnings);
    REQUIRE(samples.size() == 6);
    CHECK((samples.points - cloud.vertices).cwiseAbs().maxCoeff() <= 1e-6);
    CHECK((samples.normals - cloud.normals).cwiseAbs().maxCoeff() <= 1e-6);
    CHECK(warnings.empty());
  }
  // A mesh's vertex normals serve as well (faces ignored).
  const std::string mesh = dir.file("mesh.ply");
  hermite::saveMesh(mesh, octahedron(true));
  std::vector<std::string> warnings;
  CHECK(hermite::loadPointFile3d(mesh, warnings).size() == 6);

  const std::string bare = dir.file("bare.ply");
  hermite::saveMesh(bare, octahedron(false));
  // A mesh without vertex normals: the area-weighted face normals, outward for this closed,
  // counter-clockwise octahedron (near the vertices' directions from its centre).
  warnings.clear();
  const auto fromFaces = hermite::loadPointFile3d(bare, warnings);
  REQUIRE(fromFaces.size() == 6);
  const TriMesh reference = octahedron(false);
  const Eigen::Matrix3Xd areaWeighted = hermite::vertexNormals(reference, hermite::NormalWeighting::Area);
  CHECK((fromFaces.normals - areaWeighted).cwiseAbs().maxCoeff() <= 1e-6);  // float round trip of the vertices
  for (int v = 0; v < 6; ++v) CHECK(fromFaces.normals.col(v).dot(reference.vertices.col(v).normalized()) > 0.9);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0] == bare + ": has no vertex normals: 6 normals are the area-weighted means of the face normals "
                              "(oriented by the faces' winding)");
  // Its vertices without faces: estimated and oriented outward, with a warning.
  TriMesh bareCloud = octahedron(false);
  bareCloud.triangles.resize(3, 0);
  const std::string bareCloudPath = dir.file("bare_cloud.ply");
  hermite::saveMesh(bareCloudPath, bareCloud);
  warnings.clear();
  const auto estimated = hermite::loadPointFile3d(bareCloudPath, warnings);
  REQUIRE(estimated.size() == 6);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("has no normals (positions only): normals estimated for all 6 samples") != std::string::npos);
  CHECK_THROWS_WITH_AS(hermite::loadPointFile2d(ply, warnings),
                       (ply + ": a 3D point file (.ply) cannot be used in a 2D scene; use .xyn (x y nx ny)").c_str(),
                       InputError);
}

TEST_CASE("mesh_io: glTF node transforms, an external buffer, ushort indices, strips, fans and POINTS") {
  TempDir dir;
  // Buffer: 4 float positions of a unit square, then ushort indices 0 1 2 0 2 3 and a strip 0 1 3 2.
  std::string bin;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put<float>(bin, v, false);
  for (std::uint16_t i : {0, 1, 2, 0, 2, 3, 0, 1, 3, 2}) put<std::uint16_t>(bin, i, false);
  dir.write("square.bin", bin);
  // Node 0 translates by (10, 0, 0) and has child 1, which scales by 2 and draws the mesh.
  const std::string json = R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"translation": [10, 0, 0], "children": [1]}, {"scale": [2, 2, 2], "mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4},
                               {"attributes": {"POSITION": 0}, "indices": 2, "mode": 5},
                               {"attributes": {"POSITION": 0}, "mode": 6}]}],
    "buffers": [{"byteLength": 68, "uri": "square.bin"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 20}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 4,
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "type": "SCALAR", "count": 6},
                  {"bufferView": 1, "byteOffset": 12, "componentType": 5123, "type": "SCALAR", "count": 4}]
  })";
  const TriMesh m = hermite::loadMesh(dir.write("square.gltf", json));
  REQUIRE(m.vertexCount() == 12);  // each primitive brings its vertices
  REQUIRE(m.triangleCount() == 6);
  CHECK(m.vertices.col(2) == Eigen::Vector3d(12, 2, 0));
  CHECK(m.triangles.col(1) == Eigen::Vector3i(0, 2, 3));
  // Strip 0 1 3 2 → (0 1 3), then (1 2 3): the odd triangle swaps its last two to keep the winding.
  CHECK(m.triangles.col(2) == Eigen::Vector3i(4, 5, 7));
  CHECK(m.triangles.col(3) == Eigen::Vector3i(5, 6, 7));
  // Fan without indices over 0 1 2 3 → (0 1 2), (0 2 3).
  CHECK(m.triangles.col(4) == Eigen::Vector3i(8, 9, 10));
  CHECK(m.triangles.col(5) == Eigen::Vector3i(8, 10, 11));
  CHECK(!m.hasNormals());

  // An oriented point set as glTF POINTS with NORMAL, through the point loader.
  TriMesh cloud = octahedron(true);
  cloud.triangles.resize(3, 0);
  for (const char* ext : {".glb", ".gltf"}) {
    const std::string path = dir.file(std::string("cloud") + ext);
    hermite::saveMesh(path, cloud);
    std::vector<std::string> warnings;
    const auto samples = hermite::loadPointFile3d(path, warnings);
    REQUIRE(samples.size() == 6);
    CHECK((samples.points - cloud.vertices).cwiseAbs().maxCoeff() <= 1e-6);
    CHECK((samples.normals - cloud.normals).cwiseAbs().maxCoeff() <= 1e-6);
  }
}

TEST_CASE("mesh_io: the cube written by independent code (make_meshes.py) reads the same in every format") {
  const TriMesh reference = hermite::loadMesh(kMeshes + "/cube.off");
  for (const char* name : {"cube.obj", "cube_ascii.ply", "cube_le.ply", "cube_be.ply", "cube.gltf", "cube.glb"}) {
    CAPTURE(name);
    const TriMesh m = hermite::loadMesh(kMeshes + "/" + name);
    REQUIRE(m.vertexCount() == 8);
    CHECK(m.vertices == reference.vertices);    // 0 and 1 are exact in every encoding
    CHECK(m.triangles == reference.triangles);  // quads fan-triangulated like the listed triangles
    if (m.hasNormals()) {
      const Eigen::Matrix3Xd diagonal = ((2 * m.vertices).array() - 1).matrix().colwise().normalized();
      CHECK((m.normals - diagonal).cwiseAbs().maxCoeff() < 1e-7);  // stored as float in the GLB
    }
  }
  std::vector<std::string> warnings;
  const auto points = hermite::loadPointFile3d(kMeshes + "/cube_points.ply", warnings);
  REQUIRE(points.size() == 8);
  CHECK(points.points == reference.vertices);
}

TEST_CASE("mesh_io: a scene's data.file accepts an oriented PLY point set") {
  TempDir dir;
  const std::string scene = dir.write("scene.json", R"({"version": 1, "mode": "implicit3d", "data": {"file": ")" +
                                                        kMeshes + R"(/cube_points.ply"}})");
  std::vector<std::string> warnings;
  const auto samples = hermite::sceneSamples<3>(hermite::loadSceneFile(scene), warnings);
  REQUIRE(samples.size() == 8);
  CHECK(samples.points.col(6) == Eigen::Vector3d(1, 1, 1));
  CHECK((samples.normals.col(6) - Eigen::Vector3d(1, 1, 1).normalized()).norm() < 1e-7);
}

TEST_CASE("mesh_io: missing files, directories and endless devices are errors, not hangs") {
  TempDir dir;
  const std::string missing = dir.file("missing.ply");
  CHECK_THROWS_WITH_AS(hermite::loadMesh(missing), (missing + ": cannot open (No such file or directory)").c_str(),
                       InputError);
  const std::string folder = dir.file("folder.obj");
  fs::create_directory(folder);
  CHECK_THROWS_WITH_AS(hermite::loadMesh(folder), (folder + ": cannot open (it is a directory)").c_str(), InputError);
  const std::string zero = dir.file("zero.ply");
  fs::create_symlink("/dev/zero", zero);
  CHECK_THROWS_WITH_AS(hermite::loadMesh(zero), (zero + ": cannot read (it is a character device, not a regular file)").c_str(), InputError);
}
