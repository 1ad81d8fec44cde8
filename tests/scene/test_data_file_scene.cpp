#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/base/errors.h"
#include "scene/data_file_scene.h"
#include "scene/scene_fit.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// A sphere cloud as text: positions only (3 columns) or with its exact normals.
std::string sphereText(int n, bool normals) {
  const HermiteSamples<3> s = testing::goldenSphere(n, 0.5);
  std::string text;
  char line[200];
  for (int i = 0; i < n; ++i) {
    const Vec<3> p = s.points.col(i), m = s.normals.col(i);
    if (normals) std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(), m.x(), m.y(), m.z());
    else std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    text += line;
  }
  return text;
}

}  // namespace

TEST_CASE("data files as scenes: the extension decides, an unknown one lists the accepted ones") {
  CHECK(isSceneFilePath("a/scene.json"));
  CHECK(isSceneFilePath("SCENE.JSON"));
  for (const char* data : {"k.xyz", "k.pwn", "k.xyzn", "c.xyn", "m.ply", "m.OBJ", "m.gltf", "m.glb", "m.off"}) {
    CAPTURE(data);
    CHECK_FALSE(isSceneFilePath(data));
  }
  CHECK_THROWS_WITH_AS(isSceneFilePath("notes.txt"),
                       "notes.txt: unknown file type '.txt' (hermite-lab opens .json (a scene); .xyz, .pwn, .xyzn, "
                       ".xyn (point files); .ply, .obj, .gltf, .glb, .off (meshes and point sets))",
                       InputError);
}

TEST_CASE("data files as scenes: the default scene around a point file") {
  testing::TempDir dir("hermite_data_scene");
  const std::string path = dir.write("cloud.xyz", sphereText(400, false));
  const DataFileScene d = dataFileScene(path);
  const Scene& s = d.scene;
  CHECK(s.mode == SceneMode::Implicit3d);
  CHECK(s.data.file == path);
  CHECK(s.sourceName == path);
  CHECK(s.fit.method == FitMethod::Hrbf);
  CHECK(s.fit.kernel == KernelType::Cubic);
  CHECK(s.fit.polynomial == Polynomial::Linear);
  CHECK(s.fit.partition.enabled == PartitionSwitch::Auto);
  CHECK(d.samples == 400);
  CHECK(d.spacing > 0);
  CHECK(s.fit.radius == doctest::Approx(4 * d.spacing).epsilon(1e-12));
  REQUIRE(d.samplesBox.size() == 6);
  for (int k = 0; k < 3; ++k) {
    CHECK(d.samplesBox[k] >= -0.5 - 1e-12);
    CHECK(d.samplesBox[k] <= -0.45);
    CHECK(d.samplesBox[3 + k] <= 0.5 + 1e-12);
    CHECK(d.samplesBox[3 + k] >= 0.45);
  }
  // Positions only: one warning about the estimated normals, and the fit sees them outward.
  REQUIRE(d.warnings.size() == 1);
  CHECK(d.warnings[0].find("normals estimated for all 400 samples") != std::string::npos);
  const SceneFit<3> fit = fitScene<3>(s);
  CHECK(fit.samples.size() == 400);
  Eigen::VectorXd f;
  fit.field().evaluateBatch(Points<3>(Vec<3>(0, 0, 0)), f, nullptr);
  CHECK(f(0) < 0);  // inside the closed surface with outward normals

  // Overrides apply to the default scene; a 2D file makes a 2D scene.
  const DataFileScene o = dataFileScene(path, {"fit.kernel=wendland", "fit.radius=0.3"});
  CHECK(o.scene.fit.kernel == KernelType::Wendland);
  CHECK(o.scene.fit.radius == 0.3);
  const std::string curve = dir.write("circle.xyn", "1 0 1 0\n0 1 0 1\n-1 0 -1 0\n0 -1 0 -1\n");
  CHECK(dataFileScene(curve).scene.mode == SceneMode::Implicit2d);
  CHECK_THROWS_AS(dataFileScene(dir.write("bad.xyz", "1 2\n")), InputError);
}

// CGAL's point_set_2.xyz: six columns, every z 0 and every nz 0 — a curve's samples written as
// 3D. A 3D fit has no surface there (the mesh came out empty); the default scene is 2D.
TEST_CASE("data files as scenes: a 3D text file of curve samples in one plane z = c makes a 2D scene") {
  testing::TempDir dir("hermite_data_scene");
  std::string text = "# a circle of radius 2 in the plane z = 0.25\n";
  for (int i = 0; i < 64; ++i) {
    const double a = 2 * M_PI * i / 64;
    char line[160];
    std::snprintf(line, sizeof line, "%.17g %.17g 0.25 %.17g %.17g 0\n", 2 * std::cos(a), 2 * std::sin(a), std::cos(a),
                  std::sin(a));
    text += line;
  }
  const std::string path = dir.write("curve.xyz", text);
  const DataFileScene d = dataFileScene(path);
  CHECK(d.scene.mode == SceneMode::Implicit2d);
  CHECK(d.samples == 64);
  REQUIRE(d.warnings.size() == 1);
  CHECK(d.warnings[0] == path + ": every sample lies in one plane z = constant with its normal in that plane: read as "
                                "2D curve data (x y nx ny)");
  const SceneFit<2> fit = fitScene<2>(d.scene);
  Eigen::VectorXd f;
  fit.field().evaluateBatch(Points<2>(Vec<2>(0, 0)), f, nullptr);
  CHECK(f(0) < 0);  // inside the circle, normals outward

  // A scene file that names it in 3D keeps reading it as 3D, as before.
  nlohmann::json doc = {{"version", 1}, {"mode", "implicit3d"}, {"data", {{"file", path}}}};
  const Scene s3 = parseScene(doc, dir.file("s.json"), "");
  std::vector<std::string> warnings;
  CHECK(sceneSamples<3>(s3, warnings).size() == 64);

  // One sample off the plane, or one normal out of it: 3D data.
  const std::string off = dir.write("off.xyz", text + "0 0 0.5 0 1 0\n");
  CHECK(dataFileScene(off).scene.mode == SceneMode::Implicit3d);
  const std::string tilted = dir.write("tilted.pwn", text + "0 0 0.25 0 0.6 0.8\n");
  CHECK(dataFileScene(tilted).scene.mode == SceneMode::Implicit3d);
}

TEST_CASE("data files as scenes: a saved scene names its data relative to its own folder") {
  testing::TempDir dir("hermite_data_scene_save");
  const std::string data = dir.write("scans/cloud.xyzn", sphereText(50, true));
  const Scene s = dataFileScene(data).scene;
  const std::string saved = dir.file("scenes/deep/cloud.json");
  std::filesystem::create_directories(dir.path / "scenes/deep");
  saveSceneFile(s, saved);
  const Scene back = loadSceneFile(saved);
  CHECK(back.data.file == "../../scans/cloud.xyzn");
  CHECK(std::filesystem::equivalent(back.data.resolvedFile, data));
  CHECK(back.fit.partition.enabled == PartitionSwitch::Auto);
  std::vector<std::string> warnings;
  CHECK(sceneSamples<3>(back, warnings).size() == 50);
}
