// Writers and coordinates beyond the 32-bit float range: PLY switches to doubles, glTF (floats
// only) refuses with the file, the vertex and the value; nothing is ever written as inf.

#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "core/base/errors.h"
#include "io/mesh_file.h"

namespace fs = std::filesystem;
using hermite::TriMesh;

namespace {

TriMesh hugeTriangle(double scale) {
  TriMesh m;
  m.vertices.resize(3, 3);
  m.vertices << 0, scale, 0,  //
      0, 0, 1,                //
      0, 0, 0;
  m.triangles.resize(3, 1);
  m.triangles << 0, 1, 2;
  return m;
}

fs::path tempFile(const std::string& name) {
  return fs::temp_directory_path() / ("hermite_range_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace

TEST_CASE("PLY keeps coordinates beyond the float range as doubles; in range it stays float") {
  const fs::path big = tempFile("big.ply"), small = tempFile("small.ply");
  hermite::saveMesh(big.string(), hugeTriangle(1e39));
  const TriMesh back = hermite::loadMesh(big.string());
  REQUIRE(back.vertexCount() == 3);
  CHECK(back.vertices(0, 1) == 1e39);  // exact: written as a double
  hermite::saveMesh(small.string(), hugeTriangle(2.0));
  CHECK(fs::file_size(small) < fs::file_size(big));  // floats when they suffice
  CHECK(hermite::loadMesh(small.string()).vertices(0, 1) == 2.0);
  fs::remove(big);
  fs::remove(small);
}

TEST_CASE("glTF refuses a coordinate beyond the float range, naming the file and the value") {
  for (const char* ext : {"glb", "gltf"}) {
    const fs::path out = tempFile(std::string("big.") + ext);
    std::string message;
    try {
      hermite::saveMesh(out.string(), hugeTriangle(-5e38));
    } catch (const hermite::InputError& e) {
      message = e.what();
    }
    CHECK(message.find(out.string()) != std::string::npos);
    CHECK(message.find("-5e+38") != std::string::npos);
    CHECK(message.find("vertex 1") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}
