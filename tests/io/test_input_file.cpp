#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "support/temp_dir.h"
#include "support/input_error.h"
#include "core/base/errors.h"
#include "io/input_file.h"
#include "io/mesh_file.h"
#include "io/point_file.h"
#include "io/quoted_token.h"
#include "scene/scene_file.h"

using hermite::InputError;
namespace fs = std::filesystem;

namespace {

// Each test's own folder, named after this file's tests.
struct TempDir : hermite::testing::TempDir {
  TempDir() : hermite::testing::TempDir("hermite_input_file_test") {}
};
std::string makeFifo(const hermite::testing::TempDir& dir, const std::string& name) {
  REQUIRE(::mkfifo(dir.file(name).c_str(), 0600) == 0);
  return dir.file(name);
}

// Restores the process-wide cap when a test changes it.
struct CapGuard {
  ~CapGuard() { hermite::setMaxInputSize(hermite::kDefaultMaxInputSize); }
};

std::string errorOf(const auto& load) { return hermite::testing::inputErrorOf(load); }

}  // namespace

TEST_CASE("input_file: a regular file is read whole, an empty one as empty") {
  TempDir dir;
  const std::string bytes = std::string("a\0b\r\n", 5) + std::string(200000, 'x');
  CHECK(hermite::readInputFile(dir.write("a.txt", bytes), "test") == bytes);
  CHECK(hermite::readInputFile(dir.write("empty.txt", ""), "test").empty());
}

TEST_CASE("input_file: FIFOs, devices and folders are refused by name without blocking") {
  TempDir dir;
  const std::string fifo = makeFifo(dir, "pipe.xyz");
  CHECK(errorOf([&] { hermite::readInputFile(fifo, "point file"); }) ==
        fifo + ": cannot read (it is a FIFO, not a regular file)");
  const std::string zero = dir.file("zero.xyz");
  fs::create_symlink("/dev/zero", zero);
  CHECK(errorOf([&] { hermite::readInputFile(zero, "point file"); }) ==
        zero + ": cannot read (it is a character device, not a regular file)");
  CHECK(errorOf([&] { hermite::readInputFile(dir.path.string(), "scene"); }) ==
        dir.path.string() + ": cannot open (it is a directory)");
  const std::string missing = dir.file("missing.json");
  CHECK(errorOf([&] { hermite::readInputFile(missing, "scene"); }) ==
        missing + ": cannot open (No such file or directory)");
}

TEST_CASE("input_file: every reader goes through it (point, probe, mesh and scene files)") {
  TempDir dir;
  std::vector<std::string> warnings;
  const std::string fifoPoints = makeFifo(dir, "pipe.xyz");
  CHECK(errorOf([&] { hermite::loadPointFile3d(fifoPoints, warnings); }).find("is a FIFO, not a regular file") !=
        std::string::npos);
  const std::string urandom = dir.file("random.pwn");
  fs::create_symlink("/dev/urandom", urandom);
  CHECK(errorOf([&] { hermite::loadPointFile3d(urandom, warnings); }).find("a character device") != std::string::npos);
  const std::string fifoProbe = makeFifo(dir, "probe.txt");
  CHECK(errorOf([&] { hermite::loadProbePoints3d(fifoProbe); }).find("is a FIFO") != std::string::npos);
  const std::string fifoMesh = makeFifo(dir, "pipe.obj");
  CHECK(errorOf([&] { hermite::loadMesh(fifoMesh); }).find("is a FIFO") != std::string::npos);
  const std::string fifoScene = makeFifo(dir, "scene.json");
  CHECK(errorOf([&] { hermite::loadSceneFile(fifoScene); }) == fifoScene + ": cannot read (it is a FIFO, not a regular file)");
}

TEST_CASE("input_file: a file larger than the cap names its size, the cap and the remedy") {
  TempDir dir;
  CapGuard guard;
  const std::string points = dir.write("points.xyz", "0 0 0 0 0 1\n1 0 0 1 0 0\n");  // 24 bytes
  hermite::setMaxInputSize(24);
  CHECK(hermite::readInputFile(points, "point file").size() == 24);
  hermite::setMaxInputSize(23);
  std::vector<std::string> warnings;
  const std::string message = errorOf([&] { hermite::loadPointFile3d(points, warnings); });
  CHECK(message == points + ": 24 bytes of point file data, more than the input size limit of 23 bytes; raise the "
                            "limit with --max-input-size (e.g. --max-input-size 1G)");
  const std::string scene = dir.write("scene.json", std::string(5000, ' ') + "{}");
  hermite::setMaxInputSize(2048);
  CHECK(errorOf([&] { hermite::loadSceneFile(scene); }) ==
        scene + ": 5002 bytes (4.88 KiB) of scene data, more than the input size limit of 2048 bytes (2 KiB); raise "
                "the limit with --max-input-size (e.g. --max-input-size 1G)");
}

TEST_CASE("quoted_token: long tokens are shortened to their start and their length") {
  CHECK(hermite::quotedToken("abc") == "'abc'");
  CHECK(hermite::quotedToken(std::string(60, 'x')) == "'" + std::string(60, 'x') + "'");
  const std::string huge(20'000'000, '7');
  const std::string quoted = hermite::quotedToken(huge);
  CHECK(quoted == "'" + std::string(60, '7') + "…' (20000000 bytes)");
  // A UTF-8 character is never cut: "é" is two bytes, the 60-byte cut falls inside the 31st.
  std::string accents;
  for (int i = 0; i < 40; ++i) accents += "é";
  CHECK(hermite::shortenedToken(accents) == accents.substr(0, 60) + "… (80 bytes)");
  std::string odd = "x" + accents;  // the cut at byte 60 would split a character: 59 bytes shown
  CHECK(hermite::shortenedToken(odd) == odd.substr(0, 59) + "… (81 bytes)");
}
