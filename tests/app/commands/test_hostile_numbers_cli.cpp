// Extreme numbers and hostile outputs through the real executable: machine-readable output
// stays machine-readable, non-finite results exit 3, refusals name what is wrong.

#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"

using hermite::testing::runCli;
using hermite::testing::writeTemp;
using json = nlohmann::json;
namespace fs = std::filesystem;

TEST_CASE("fit --json of one sample, or of identical samples, prints JSON and nothing from LAPACK") {
  const std::string one = writeTemp("one_sample.json", R"({"version": 1, "mode": "implicit3d",
    "data": {"points": [[0.5, 0.25, 1]], "normals": [[0, 0, 1]]}, "fit": {"kernel": "cubic"}})");
  const std::string same = writeTemp("same_samples.json", R"({"version": 1, "mode": "implicit3d",
    "data": {"points": [[2, 2, 2], [2, 2, 2], [2, 2, 2]], "normals": [[0, 1, 0], [0, 1, 0], [0, 1, 0]]},
    "fit": {"kernel": "cubic"}})");
  for (const std::string& scene : {one, same}) {
    CAPTURE(scene);
    const auto r = runCli("fit " + scene + " --json --coefficients");
    CAPTURE(r.err);
    CHECK(r.out.find("On entry") == std::string::npos);
    if (r.rc == 0) {
      const json j = json::parse(r.out);  // throws (fails the test) when stdout is not JSON
      CHECK(j["max_abs_f"].get<double>() <= 1e-12);
    } else {
      CHECK(r.out.empty());
      CHECK(r.err.find("On entry") == std::string::npos);
    }
  }
}

TEST_CASE("eval far from a compact kernel gives the polynomial part; an overflowing field exits 3") {
  const std::string probes = writeTemp("far_probes.txt", "1e160 -2e160 3e159\n0.1 0.2 0.3\n");
  const std::string wendland = writeTemp("far_wendland.json", R"({"version": 1, "mode": "implicit3d",
    "data": {"preset": "sphere6"}, "fit": {"kernel": "wendland", "radius": 3, "polynomial": "linear"}})");
  const auto ok = runCli("eval " + wendland + " --at " + probes);
  CAPTURE(ok.err);
  CHECK(ok.rc == 0);
  CHECK(ok.out.find("nan") == std::string::npos);
  CHECK(ok.out.find("inf") == std::string::npos);

  const std::string cubic = writeTemp("far_cubic.json", R"({"version": 1, "mode": "implicit3d",
    "data": {"preset": "sphere6"}, "fit": {"kernel": "cubic"}})");
  const auto bad = runCli("eval " + cubic + " --at " + probes);  // x³ at 1e160 overflows
  CHECK(bad.rc == 3);
  CHECK(bad.out.empty());
  CHECK(bad.err.find("not finite") != std::string::npos);
  CHECK(bad.err.find("probe 1") != std::string::npos);
}

TEST_CASE("scene numbers out of range: 1e400 and smoothing 1e308 exit 1 naming the key") {
  const std::string huge = writeTemp("huge_number.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "circle"}, "fit": {"kernel": "gaussian", "radius": 1e400}})");
  const auto r1 = runCli("fit " + huge + " --json");
  CHECK(r1.rc == 1);
  CHECK(r1.err.find("fit.radius") != std::string::npos);
  const std::string smooth = writeTemp("huge_smoothing.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "circle"}, "fit": {"kernel": "gaussian", "smoothing": 1e308}})");
  const auto r2 = runCli("fit " + smooth + " --json");
  CHECK(r2.rc == 1);
  CHECK(r2.err.find("fit.smoothing") != std::string::npos);
  // With --json standard output holds only the error object (no partial fit report).
  const nlohmann::json j = nlohmann::json::parse(r2.out);
  CHECK(j["exit_code"] == 1);
  CHECK(j["key"] == "fit.smoothing");
}

TEST_CASE("max_points_per_box near INT_MAX fits one box instead of wrapping 6·max") {
  const std::string scene = writeTemp("huge_box.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "circle", "count": 40},
    "fit": {"kernel": "gaussian", "radius": 0.5, "partition": {"enabled": true, "max_points_per_box": 2147483647}}})");
  const auto r = runCli("fit " + scene + " --json");
  CAPTURE(r.err);
  REQUIRE(r.rc == 0);
  CHECK(json::parse(r.out)["partition"]["boxes"].get<int>() == 1);
}
