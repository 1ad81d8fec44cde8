// Every command that takes a scene also takes a point or mesh file (docs/cli.md, "Data files in
// place of a scene"): the default scene around it, estimated normals, the size switch.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/test_data.h"

using hermite::testing::runCli;
using hermite::testing::writeTemp;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A sphere cloud of radius 0.5 as .xyz: positions only, or with every normal zero (blobby.xyz).
std::string sphereFile(const std::string& name, int n, const char* normals) {
  const hermite::HermiteSamples<3> s = hermite::testing::goldenSphere(n, 0.5);
  std::string text;
  char line[200];
  for (int i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g%s\n", s.points(0, i), s.points(1, i), s.points(2, i), normals);
    text += line;
  }
  return writeTemp(name, text);
}

json fitJson(const std::string& args) {
  const auto r = runCli("fit " + args + " --json");
  REQUIRE_MESSAGE(r.rc == 0, r.err);
  return json::parse(r.out);
}

}  // namespace

TEST_CASE("data files: fit FILE builds the default scene, estimates missing and zero normals") {
  const std::string bare = sphereFile("data_bare.xyz", 300, "");
  const json j = fitJson(bare);
  CHECK(j["n_samples"] == 300);
  CHECK(j["kernel"] == "cubic");
  CHECK(j["partition_chosen"] == "dense");
  CHECK(j["data_reach_mask"] == true);  // a file of at least 50 samples, fitted globally
  CHECK(j["max_abs_f"].get<double>() < 1e-6);
  REQUIRE(j["warnings"].size() == 1);
  CHECK(contains(j["warnings"][0], "normals estimated for all 300 samples"));

  // Six columns, all normals zero (CGAL's blobby.xyz): estimated too; the text report names the file.
  const std::string zeros = sphereFile("data_zeros.xyz", 300, " 0 0 0");
  const auto text = runCli("fit " + zeros);
  REQUIRE(text.rc == 0);
  CHECK(contains(text.out, "scene        " + zeros + " (implicit3d, 300 samples"));
  CHECK(contains(text.out, "300 of 300 normals are zero"));
  CHECK(contains(text.out, "data reach   the surface ends within 3 local spacings of the samples"));
  CHECK(fitJson(zeros + " --set fit.reach_mask=false")["data_reach_mask"] == false);

  // A mesh without vertex normals is data too: area-weighted face normals.
  const std::string off = writeTemp("data_tetra.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                                      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const json m = fitJson(off);
  CHECK(m["n_samples"] == 4);
  CHECK(contains(m["warnings"][0], "area-weighted means of the face normals"));
}

TEST_CASE("data files: fit.partition.enabled \"auto\" picks the fit by size, false keeps the dense fit") {
  // 3 000 samples: 12 004 unknowns, above the 10 000 of "auto".
  const std::string big = sphereFile("data_big.xyz", 3000, "");
  const json pu = fitJson(big);
  CHECK(pu["partition_chosen"] == "pu");
  CHECK(pu["data_reach_mask"] == false);  // the partition of unity has its reach of its own
  CHECK(pu["partition"].is_object());
  bool said = false;
  for (const auto& w : pu["warnings"]) said |= contains(w, "3000 samples make a global fit of 12004 unknowns");
  CHECK(said);
  // The same file with a forced dense fit is dense (it fits in memory here).
  const json dense = fitJson(sphereFile("data_mid.xyz", 1000, "") + " --set fit.partition.enabled=false");
  CHECK(dense["partition_chosen"] == "dense");
  CHECK(dense["partition"].is_null());
}

TEST_CASE("data files: eval, mesh, render and sweep take a point file") {
  const std::string cloud = sphereFile("data_cloud.xyz", 200, "");
  const std::string probes = writeTemp("data_probes.txt", "0 0 0\n0.5 0 0\n1 0 0\n");
  const auto ev = runCli("eval " + cloud + " --at " + probes);
  REQUIRE_MESSAGE(ev.rc == 0, ev.err);
  double f[3][4];
  CHECK(std::sscanf(ev.out.c_str(), "%lf %lf %lf %lf\n%lf %lf %lf %lf\n%lf %lf %lf %lf", &f[0][0], &f[0][1], &f[0][2],
                    &f[0][3], &f[1][0], &f[1][1], &f[1][2], &f[1][3], &f[2][0], &f[2][1], &f[2][2], &f[2][3]) == 12);
  CHECK(f[0][0] < 0);                  // inside
  CHECK(std::abs(f[1][0]) < 1e-2);     // on the sphere, between samples of spacing ≈ 0.06
  CHECK(f[2][0] > 0);                  // outside

  const std::string mesh = (fs::temp_directory_path() / "hermite_data_mesh.ply").string();
  const auto me = runCli("mesh " + cloud + " -o " + mesh + " --resolution 24");
  REQUIRE_MESSAGE(me.rc == 0, me.err);
  CHECK(contains(me.out, "closed manifold"));
  CHECK(fs::file_size(mesh) > 0);

  const std::string png = (fs::temp_directory_path() / "hermite_data_render.png").string();
  const auto re = runCli("render " + cloud + " -o " + png + " --size 64x48");
  REQUIRE_MESSAGE(re.rc == 0, re.err);
  CHECK(fs::file_size(png) > 0);

  const fs::path dir = fs::temp_directory_path() / "hermite_data_sweep";
  fs::remove_all(dir);
  const auto sw = runCli("sweep " + cloud + " --radii 0.3:0.6:2 --size 32x24 -o " + dir.string());
  REQUIRE_MESSAGE(sw.rc == 0, sw.err);
  CHECK(fs::exists(dir / "diagnostics.csv"));

  // Progress goes to a terminal only: nothing on a redirected stderr but the estimation warning,
  // which each command gives (docs/cli.md, "Data files in place of a scene").
  CHECK_FALSE(contains(me.err, "fitting"));
  const std::string estimated = "warning: " + cloud + ": has no normals (3 columns): normals estimated for all 200";
  for (const auto* r : {&ev, &me, &re, &sw}) CHECK_MESSAGE(contains(r->err, estimated), r->err);
  CHECK(sw.err.find(estimated) == sw.err.rfind(estimated));  // once, not once per radius
  CHECK_FALSE(contains(me.err, "partition"));  // the fit's own warnings are `fit`'s to list
}

TEST_CASE("data files: the program without a display fits the file; an unknown extension lists the accepted ones") {
  const std::string cloud = sphereFile("data_default.xyz", 100, "");
  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  const auto r = runCli(cloud);
  if (!saved.empty()) ::setenv("DISPLAY", saved.c_str(), 1);
  CHECK(r.rc == 0);
  CHECK(contains(r.out, "100 samples"));

  const std::string notes = writeTemp("data_notes.txt", "1 2 3\n");
  const auto bad = runCli("fit " + notes);
  CHECK(bad.rc == 1);
  CHECK(contains(bad.err, "unknown file type '.txt'"));
  CHECK(contains(bad.err, ".json (a scene); .xyz, .pwn, .xyzn, .xyn (point files)"));
}
