#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_runner.h"

using hermite::testing::runCli;
using hermite::testing::writeTemp;
namespace fs = std::filesystem;

namespace {

// A fresh FIFO beside the other temporary files of runCli.
std::string makeFifo(const std::string& name) {
  const std::string path = writeTemp(name, "");
  fs::remove(path);
  REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
  return path;
}

const char* kTorusScene = R"({"version": 1, "mode": "implicit3d", "data": {"preset": "torus", "count": 60},
  "fit": {"kernel": "cubic", "radius": 1.0, "polynomial": "linear"}})";

}  // namespace

TEST_CASE("cli input: a FIFO scene, point file or probe file is an input error, never a hang") {
  const std::string fifo = makeFifo("fifo_scene.json");
  auto r = runCli("fit " + fifo);
  CHECK(r.rc == 1);
  CHECK(r.err == "error: " + fifo + ": cannot read (it is a FIFO, not a regular file)\n");

  const std::string points = makeFifo("fifo_points.xyz");
  const std::string scene = writeTemp("fifo_data.json", R"({"version": 1, "mode": "implicit3d", "data": {"file": ")" +
                                                            fs::path(points).filename().string() + R"("}})");
  r = runCli("fit " + scene);
  CHECK(r.rc == 1);
  CHECK(r.err.find(points + ": cannot read (it is a FIFO, not a regular file)") != std::string::npos);

  const std::string torus = writeTemp("fifo_torus.json", kTorusScene);
  const std::string zero = writeTemp("zero_probe.txt", "");
  fs::remove(zero);
  fs::create_symlink("/dev/zero", zero);
  r = runCli("eval " + torus + " --at " + zero);
  CHECK(r.rc == 1);
  CHECK(r.err.find(zero + ": cannot read (it is a character device, not a regular file)") != std::string::npos);
  fs::remove(fifo);
  fs::remove(points);
  fs::remove(zero);
}

TEST_CASE("cli input: --max-input-size caps every input file and takes 512M, 8G, …") {
  const std::string torus = writeTemp("cap_torus.json", kTorusScene);
  const std::string probes = writeTemp("cap_probes.txt", "0 0 0\n1 0 0\n");
  auto r = runCli("fit " + torus + " --max-input-size 100");
  CHECK(r.rc == 1);
  CHECK(r.err.find(torus + ": " + std::to_string(fs::file_size(torus)) +
                   " bytes of scene data, more than the input size limit of 100 bytes; raise the limit with "
                   "--max-input-size") != std::string::npos);
  r = runCli("eval " + torus + " --at " + probes + " --max-input-size 500");
  CHECK(r.rc == 0);
  r = runCli("eval " + torus + " --at " + probes + " --max-input-size 11");
  CHECK(r.rc == 1);
  CHECK(r.err.find(torus + ": ") != std::string::npos);  // the scene comes first
  for (const char* good : {"512M", "8G", "4096", "1KiB", "2gb"}) {
    CAPTURE(good);
    CHECK(runCli("fit " + torus + " --max-input-size " + good).rc == 0);
  }
  for (const char* bad : {"0", "-1", "8X", "G", "1.5G", "99999999999T"}) {
    CAPTURE(bad);
    r = runCli("fit " + torus + " --max-input-size " + bad);
    CHECK(r.rc == 2);
    CHECK(r.err.find("--max-input-size") != std::string::npos);
  }
}

TEST_CASE("cli input: holefill refuses a glTF whose buffer lies outside its folder") {
  const fs::path dir = fs::path(writeTemp("holefill_escape.keep", "")).parent_path() / "holefill_escape";
  fs::create_directories(dir / "model");
  {
    // A valid triangle buffer one folder up: read, it would make a mesh.
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::ofstream(dir / "secret.bin", std::ios::binary).write(reinterpret_cast<const char*>(v), sizeof(v));
    std::ofstream(dir / "model/m.gltf") << R"({"asset": {"version": "2.0"},
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "buffers": [{"byteLength": 36, "uri": "..%2fsecret.bin"}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3}]})";
  }
  const std::string out = (dir / "out.obj").string();
  const auto r = runCli("holefill " + (dir / "model/m.gltf").string() + " -o " + out);
  CHECK(r.rc == 1);
  CHECK(r.err.find((dir / "model/m.gltf").string() + ": uri '../secret.bin' leaves the folder of the glTF file") !=
        std::string::npos);
  CHECK(!fs::exists(out));
  fs::remove_all(dir);
}
