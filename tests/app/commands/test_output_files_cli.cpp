// Output files through the real executable: the format follows the extension, a reused sweep
// folder needs --overwrite, an overwritten file keeps its mode.

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

TEST_CASE("render refuses an output extension other than .png before any work") {
  const std::string scene = writeTemp("render_ext.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "circle"}})");
  const fs::path out = fs::path(scene).parent_path() / "picture.jpg";
  const auto r = runCli("render " + scene + " -o " + out.string());
  CHECK(r.rc == 2);
  CHECK(r.err.find(".png") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("sweep refuses a non-empty directory; --overwrite replaces only its own files") {
  const fs::path dir = fs::temp_directory_path() / ("hermite_sweep_reuse_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string scene = writeTemp("sweep_reuse.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "circle"}, "fit": {"kernel": "gaussian", "polynomial": "none"}})");
  const std::string args = "sweep " + scene + " --size 32x24 -o " + dir.string();
  REQUIRE(runCli(args + " --radii 0.3:0.6:2").rc == 0);
  CHECK(fs::exists(dir / "r_01_0.6.png"));
  std::ofstream(dir / "notes.txt") << "mine";
  const auto refused = runCli(args + " --radii 0.4:0.4:1");
  CHECK(refused.rc == 4);
  CHECK(refused.err.find("--overwrite") != std::string::npos);
  CHECK(fs::exists(dir / "r_01_0.6.png"));
  const auto again = runCli(args + " --radii 0.4:0.4:1 --overwrite");
  CAPTURE(again.err);
  CHECK(again.rc == 0);
  CHECK_FALSE(fs::exists(dir / "r_01_0.6.png"));  // the earlier sweep's images are gone
  CHECK(fs::exists(dir / "r_00_0.4.png"));
  CHECK(fs::exists(dir / "notes.txt"));  // not the sweep's: kept
  fs::remove_all(dir);
}

TEST_CASE("mesh into a 0600 file keeps the mode") {
  const std::string scene = writeTemp("mesh_mode.json", R"({"version": 1, "mode": "implicit3d",
    "data": {"preset": "sphere6"}, "fit": {"kernel": "cubic"}})");
  const fs::path out = fs::path(scene).parent_path() / "private.ply";
  std::ofstream(out) << "old";
  REQUIRE(::chmod(out.c_str(), 0600) == 0);
  const auto r = runCli("mesh " + scene + " --resolution 16 -o " + out.string());
  CAPTURE(r.err);
  REQUIRE(r.rc == 0);
  struct stat st {};
  REQUIRE(::stat(out.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0600);
  CHECK(fs::file_size(out) > 3);
  fs::remove(out);
}
