#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "support/temp_dir.h"
#include "support/input_error.h"
#include "core/base/errors.h"
#include "io/gltf_file.h"
#include "io/gltf_file_access.h"
#include "io/mesh_file.h"

using hermite::InputError;
namespace fs = std::filesystem;

namespace {

// Each test's own folder, named after this file's tests.
struct TempDir : hermite::testing::TempDir {
  TempDir() : hermite::testing::TempDir("hermite_gltf_access_test") { fs::create_directories(path / "model" / "sub"); }
};

// x y z of a triangle, little-endian floats (36 bytes).
std::string trianglePositions() {
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string bytes(sizeof(v), '\0');
  std::memcpy(bytes.data(), v, sizeof(v));
  return bytes;
}

// One triangle read from the buffer at `uri` (byteLength 36), optionally with an image at `imageUri`.
std::string triangleGltf(const std::string& uri, const std::string& imageUri = "") {
  std::string images = imageUri.empty() ? "" : R"(, "images": [{"uri": ")" + imageUri + R"("}])";
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "buffers": [{"byteLength": 36, "uri": ")" + uri + R"("}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3}])" + images + "}";
}

std::string errorOf(const std::string& path) {
  return hermite::testing::inputErrorOf([&] { hermite::loadMesh(path); });
}

}  // namespace

TEST_CASE("gltf_file_access: buffers inside the glTF file's folder are read") {
  TempDir dir;
  dir.write("model/sub/tri.bin", trianglePositions());
  for (const char* uri : {"sub/tri.bin", "sub%2Ftri.bin", "./sub/../sub/tri.bin"}) {
    CAPTURE(uri);
    dir.write("model/m.gltf", triangleGltf(uri));
    CHECK(hermite::loadMesh((dir.path / "model/m.gltf").string()).vertexCount() == 3);
  }
  // A symlink that stays inside the folder is fine.
  fs::create_symlink("sub/tri.bin", dir.path / "model/link.bin");
  dir.write("model/m.gltf", triangleGltf("link.bin"));
  CHECK(hermite::loadMesh((dir.path / "model/m.gltf").string()).vertexCount() == 3);
  // Embedded data: URIs keep working (the writer uses them).
  const hermite::TriMesh mesh = hermite::loadMesh((dir.path / "model/m.gltf").string());
  CHECK(hermite::readGltf(hermite::writeGltf(mesh, false, "x.gltf"), "x.gltf").vertexCount() == 3);
}

TEST_CASE("gltf_file_access: URIs that leave the folder are refused, naming the file and the uri") {
  TempDir dir;
  dir.write("outside.bin", trianglePositions());  // a file that must not be reachable from model/
  const std::string gltf = (dir.path / "model/m.gltf").string();
  struct Case {
    std::string uri, reason;
  };
  const Case cases[] = {
      {"../outside.bin", "uri '../outside.bin' leaves the folder of the glTF file"},
      {"../../../../../../../../etc/passwd", "leaves the folder"},
      {"%2e%2e%2foutside.bin", "uri '../outside.bin' leaves the folder"},
      {"%2E%2E/%2E%2E/%2E%2E/%2E%2E/%2E%2E/%2E%2E/etc/passwd", "leaves the folder"},
      {"sub/../../outside.bin", "leaves the folder"},
      {"/etc/passwd", "uri '/etc/passwd' is an absolute path"},
      {(dir.path / "outside.bin").string(), "is an absolute path"},
      {"file:///etc/passwd", "uri 'file:///etc/passwd' has a scheme (file:)"},
      {"file:outside.bin", "has a scheme (file:)"},
      {"http://example.com/a.bin", "has a scheme (http:)"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.uri);
    dir.write("model/m.gltf", triangleGltf(c.uri));
    const std::string message = errorOf(gltf);
    CAPTURE(message);
    CHECK(message.rfind(gltf + ": ", 0) == 0);
    CHECK(message.find(c.reason) != std::string::npos);
    CHECK(message.find("a glTF file may only refer to data: URIs and to files in its own folder") != std::string::npos);
  }
}

TEST_CASE("gltf_file_access: a symlink inside the folder that points outside is refused") {
  TempDir dir;
  dir.write("outside.bin", trianglePositions());
  fs::create_symlink(dir.path / "outside.bin", dir.path / "model/escape.bin");
  fs::create_directory_symlink(dir.path, dir.path / "model/sub/up");
  const std::string gltf = (dir.path / "model/m.gltf").string();
  for (const char* uri : {"escape.bin", "sub/up/outside.bin"}) {
    CAPTURE(uri);
    dir.write("model/m.gltf", triangleGltf(uri));
    const std::string message = errorOf(gltf);
    CAPTURE(message);
    CHECK(message.find("resolves to " + (fs::canonical(dir.path) / "outside.bin").string() +
                       ", outside the folder of the glTF file") != std::string::npos);
  }
}

TEST_CASE("gltf_file_access: images obey the same policy, special files are named") {
  TempDir dir;
  dir.write("model/tri.bin", trianglePositions());
  const std::string gltf = (dir.path / "model/m.gltf").string();
  dir.write("model/m.gltf", triangleGltf("tri.bin", "../../../../../../../etc/passwd"));
  CHECK(errorOf(gltf).find("uri '../../../../../../../etc/passwd' leaves the folder") != std::string::npos);
  // A missing image is no error (images are not read for geometry); a missing buffer is.
  dir.write("model/m.gltf", triangleGltf("tri.bin", "missing.png"));
  CHECK(hermite::loadMesh(gltf).vertexCount() == 3);
  fs::create_symlink("/dev/zero", dir.path / "model/zero.bin");
  dir.write("model/m.gltf", triangleGltf("zero.bin"));
  CHECK(errorOf(gltf).find("uri 'zero.bin' resolves to /dev/zero, outside the folder") != std::string::npos);
  REQUIRE(::mkfifo((dir.path / "model/pipe.bin").c_str(), 0600) == 0);
  dir.write("model/m.gltf", triangleGltf("pipe.bin"));
  CHECK(errorOf(gltf).find("uri 'pipe.bin': " + (dir.path / "model/pipe.bin").string() +
                           ": cannot read (it is a FIFO, not a regular file)") != std::string::npos);
}

TEST_CASE("gltf_file_access: the working directory is never searched for a buffer") {
  TempDir dir;
  dir.write("tri.bin", trianglePositions());  // in the working directory, not beside the glTF
  dir.write("model/m.gltf", triangleGltf("tri.bin"));
  const fs::path before = fs::current_path();
  fs::current_path(dir.path);
  const std::string message = errorOf("model/m.gltf");
  fs::current_path(before);
  CHECK(message.find("File not found") != std::string::npos);
}

TEST_CASE("gltf_file: a 30000-deep node chain is read; deeper than the limit is an error, not a crash") {
  auto chain = [](int depth) {
    std::string nodes;
    for (int i = 0; i + 1 < depth; ++i) nodes += R"({"children": [)" + std::to_string(i + 1) + "]},";
    nodes += R"({"mesh": 0, "translation": [1, 2, 3]})";
    const std::string positions = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [)" + nodes +
           R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "buffers": [{"byteLength": 36, "uri": ")" + positions + R"("}],
           "bufferViews": [{"buffer": 0, "byteLength": 36}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3}]})";
  };
  const hermite::TriMesh mesh = hermite::readGltf(chain(30000), "chain.gltf");
  REQUIRE(mesh.vertexCount() == 3);
  CHECK(mesh.vertices.col(1) == Eigen::Vector3d(2, 2, 3));  // (1, 0, 0) moved by the leaf's translation
  CHECK_THROWS_WITH_AS(hermite::readGltf(chain(100001), "chain.gltf"),
                       "chain.gltf: node 100000 is 100001 levels deep in the node tree, more than this reader "
                       "supports (100000)",
                       InputError);
}

TEST_CASE("gltf_file: JSON nested deeper than any glTF needs is refused before tinygltf copies it") {
  const std::string deep = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
  CHECK_THROWS_WITH_AS(hermite::readGltf(deep, "deep.gltf"),
                       "deep.gltf: JSON nested more than 256 levels deep (at byte 295), deeper than this reader supports",
                       InputError);
  // Brackets inside strings do not count.
  const std::string inString = R"({"asset": {"version": "2.0", "generator": ")" + std::string(1000, '[') + R"("}})";
  CHECK_THROWS_WITH_AS(hermite::readGltf(inString, "s.gltf"), "s.gltf: no mesh primitives with vertices", InputError);
}
