#include <doctest/doctest.h>

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/gui/fit_worker.h"
#include "core/base/memory_check.h"
#include "io/system_memory.h"
#include "scene/scene_file.h"
#include "support/cli_runner.h"

using hermite::testing::readAll;
using hermite::testing::writeTemp;

namespace {

struct LimitedRun {
  int rc = -1;
  std::string err;
  double seconds = 0;
};

// Runs hermite-lab under an address-space limit (`ulimit -v`, KiB), stdout discarded.
LimitedRun runLimited(const std::string& args, long limitKiB) {
  const std::string err = writeTemp("limited.err", "");
  const std::string cmd = "ulimit -v " + std::to_string(limitKiB) + "; " + std::string(HERMITE_EXE) + " " + args +
                          " > /dev/null 2> " + err;
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(cmd.c_str());
  LimitedRun r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = readAll(err);
  return r;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

constexpr long kLimitKiB = 4L << 20;  // 4 GiB of address space

const char* kSphereScene = R"({"version": 1, "mode": "implicit3d", "data": {"preset": "sphere", "count": 200},
                               "fit": {"kernel": "cubic", "radius": 1.0, "polynomial": "linear"}})";

}  // namespace

TEST_CASE("work beyond the memory limit is refused before it starts: exit 4, the sizes and the remedy") {
  const std::string scene = writeTemp("memory_sphere.json", kSphereScene);
  SUBCASE("mesh --resolution 4096") {
    const LimitedRun r = runLimited("mesh " + scene + " -o " + writeTemp("m.ply", "") + " --resolution 4096", kLimitKiB);
    CHECK(r.rc == 4);
    CHECK(contains(r.err, "environment error: marching cubes at resolution 4096"));
    CHECK(contains(r.err, "GB available (RLIMIT_AS)"));
    CHECK(contains(r.err, "use a lower resolution"));
    CHECK(r.seconds < 10);
  }
  SUBCASE("render --size 12000x12000") {
    const LimitedRun r = runLimited("render " + scene + " -o " + writeTemp("r.png", "") + " --size 12000x12000", kLimitKiB);
    CHECK(r.rc == 4);
    CHECK(contains(r.err, "rendering 12000 x 12000 pixels"));
    CHECK(contains(r.err, "needs 29 GB"));  // 150 MB + 200 bytes per pixel
    CHECK(contains(r.err, "use a smaller --size"));
    CHECK(r.seconds < 10);
  }
  SUBCASE("patch-table --samples 100000") {
    const LimitedRun r = runLimited("patch-table --samples 100000", kLimitKiB);
    CHECK(r.rc == 4);
    CHECK(contains(r.err, "the patch study with 100000 x 100000 samples per patch"));
    CHECK(contains(r.err, "needs 320 GB"));
    CHECK(contains(r.err, "--samples"));
    CHECK(r.seconds < 10);
  }
  SUBCASE("a global fit of 50 000 points") {
    const std::string big = writeTemp("memory_big.json", R"({"version": 1, "mode": "implicit3d",
        "data": {"preset": "sphere", "count": 50000}, "fit": {"kernel": "gaussian", "radius": 1.0, "polynomial": "linear",
        "partition": {"enabled": false}}})");
    for (const char* command : {"fit", "sweep"}) {
      CAPTURE(command);
      const std::string dir = (std::filesystem::temp_directory_path() / "hermite_sweep_refused").string();
      const std::string extra = std::string(command) == "sweep" ? " --radii 0.5:1:2 -o " + dir : "";
      const LimitedRun r = runLimited(std::string(command) + " " + big + extra, kLimitKiB);
      CHECK(r.rc == 4);
      CHECK(contains(r.err, "the dense fit of 200004 unknowns"));
      CHECK(contains(r.err, "needs 32"));  // 320 GB + 128 MiB per BLAS thread
      CHECK(contains(r.err, "fit.partition.enabled"));
      CHECK(r.seconds < 20);
    }
  }
}

TEST_CASE("--threads above the cores available is lowered to them, with a note") {
  const std::string scene = writeTemp("threads_sphere.json", kSphereScene);
  const unsigned cores = std::thread::hardware_concurrency();
  const auto r = hermite::testing::runCli("fit " + scene + " --threads 4096 --json");
  CHECK(r.rc == 0);
  CHECK(contains(r.err, "note: --threads 4096 is more than the"));
  CHECK(contains(r.err, "using "));
  CHECK(cores >= 1);
  const auto ok = hermite::testing::runCli("fit " + scene + " --threads 1 --json");
  CHECK(ok.rc == 0);
  CHECK_FALSE(contains(ok.err, "note:"));
}

TEST_CASE("--threads that is not a whole number is a usage error naming the option, not an internal error") {
  const std::string scene = writeTemp("threads_bad_sphere.json", kSphereScene);
  for (const char* value : {"abc", "3x", "99999999999999999999999", "-1"}) {
    CAPTURE(value);
    const auto r = hermite::testing::runCli("fit " + scene + " --threads " + value);
    CHECK(r.rc == 2);
    CHECK(contains(r.err, "--threads"));
    CHECK(contains(r.err, value));
    CHECK_FALSE(contains(r.err, "internal error"));
  }
}

TEST_CASE("under an address-space limit near the fit's size the process never hangs: it fits or exits 4") {
  // 2 000 points: a 512 MB system matrix. The limits run from a clear refusal to a clear fit,
  // through the boundary where the check passes and a later allocation may still fail.
  const std::string scene = writeTemp("oom_sphere.json", R"({"version": 1, "mode": "implicit3d",
      "data": {"preset": "sphere", "count": 2000}, "fit": {"kernel": "cubic", "radius": 1.0, "polynomial": "linear",
      "partition": {"enabled": false}}})");
  for (long mib : {600L, 900L, 950L}) {
    for (const char* threads : {"1", "4096"}) {
      CAPTURE(mib);
      CAPTURE(threads);
      const LimitedRun r = runLimited("fit " + scene + " --threads " + threads, mib << 10);
      CHECK((r.rc == 0 || r.rc == 4));
      if (r.rc == 4) CHECK(contains(r.err, "environment error:"));
      CHECK(r.seconds < 60);
    }
  }
}

TEST_CASE("the GUI's fit of a scene too large for this machine ends in the refusal as its message") {
  hermite::setAvailableMemorySource(hermite::querySystemMemory);
  const hermite::Scene scene = hermite::parseScene(nlohmann::json::parse(R"({"version": 1, "mode": "implicit3d",
      "data": {"preset": "sphere", "count": 50000}, "fit": {"kernel": "cubic", "radius": 1.0, "polynomial": "linear",
      "partition": {"enabled": false}}})"),
                                                   "big.json", ".");
  const auto outcome = hermite::app::fitOutcome(scene);
  hermite::setAvailableMemorySource(nullptr);
  CHECK_FALSE(outcome->ok());
  CHECK(contains(outcome->error, "the dense fit of 200004 unknowns"));
  CHECK(contains(outcome->error, "fit.partition.enabled"));
}
