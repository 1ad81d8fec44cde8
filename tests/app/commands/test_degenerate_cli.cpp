// Degenerate fields at the command line (issue 19 item 3): `fit --json` warns with cause and
// remedy, `mesh` warns and never reports a closed manifold made of the flat region's noise.

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_runner.h"
#include "support/temp_dir.h"

using namespace hermite::testing;

namespace {

std::string teachingScene(const std::string& name) { return std::string(HERMITE_SOURCE_DIR) + "/assets/scenes/" + name; }

bool hasDegenerateWarning(const nlohmann::json& j) {
  for (const auto& w : j["warnings"])
    if (w.get<std::string>().rfind("degenerate field:", 0) == 0 &&
        w.get<std::string>().find("add a polynomial or increase r") != std::string::npos)
      return true;
  return false;
}

}  // namespace

TEST_CASE("fit --json: the degenerate teaching scenes warn, with the flat fraction; a well-posed one does not") {
  for (const char* name : {"wendland_sphere6_r1_none.json", "wendland_twotori_120pts_r0.6_none.json",
                           "gaussian2d_40pts_r0.02_none.json"}) {
    CAPTURE(name);
    const CliResult r = runCli("fit --json " + teachingScene(name));
    REQUIRE(r.rc == 0);
    const nlohmann::json j = nlohmann::json::parse(r.out);
    CHECK(hasDegenerateWarning(j));
    CHECK(j["degenerate_field"]["degenerate"].get<bool>());
    CHECK(j["degenerate_field"]["flat_fraction"].get<double>() > 0.25);
  }
  const CliResult ok = runCli("fit --json " + teachingScene("wendland_sphere6_r2_none.json"));
  REQUIRE(ok.rc == 0);
  const nlohmann::json j = nlohmann::json::parse(ok.out);
  CHECK_FALSE(hasDegenerateWarning(j));
  CHECK_FALSE(j["degenerate_field"]["degenerate"].get<bool>());
  // A kernel that grows with distance is never flat away from the data: the check is skipped.
  const CliResult cubic = runCli("fit --json " + teachingScene("polyharmonic_bunny_64pts_quadratic.json"));
  REQUIRE(cubic.rc == 0);
  const nlohmann::json c = nlohmann::json::parse(cubic.out);
  CHECK_FALSE(c["degenerate_field"]["degenerate"].get<bool>());
  CHECK(c["degenerate_field"].contains("skipped"));
}

TEST_CASE("mesh: a degenerate field warns and its mesh is not called a closed manifold") {
  TempDir tmp;
  const CliResult r = runCli("mesh " + teachingScene("wendland_sphere6_r1_none.json") + " -o " +
                             (tmp.path / "m.ply").string() + " --resolution 32");
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("closed manifold") == std::string::npos);
  const bool saysDegenerate = r.out.find("the field is degenerate") != std::string::npos ||
                              r.out.find("open (degenerate regions left out)") != std::string::npos;
  CHECK(saysDegenerate);
  CHECK(r.err.find("warning: degenerate field:") != std::string::npos);
}
