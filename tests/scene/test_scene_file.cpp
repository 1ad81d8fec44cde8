#include <doctest/doctest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/temp_dir.h"
#include "core/base/errors.h"
#include "scene/scene_file.h"

using hermite::InputError;
using hermite::Scene;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kFixtures = HERMITE_FIXTURES;

// Each test's own folder, named after this file's tests.
struct TempDir : hermite::testing::TempDir {
  TempDir() : hermite::testing::TempDir("hermite_scene_test") {}
};

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// A minimal valid scene with extra top-level members appended.
std::string scene3d(const std::string& extra = "") {
  return R"({"version": 1, "mode": "implicit3d", "data": {"preset": "sphere6"})" +
         (extra.empty() ? std::string() : ", " + extra) + "}";
}
std::string scene2d(const std::string& extra = "") {
  return R"({"version": 1, "mode": "implicit2d", "data": {"preset": "circle"})" +
         (extra.empty() ? std::string() : ", " + extra) + "}";
}

Scene parse(const std::string& text) { return hermite::parseScene(json::parse(text), "x.json", "/base/dir"); }

// The message of the InputError that parsing `text` throws, or "<no error>".
std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Every field differs from its default.
Scene nonDefaultScene3d() {
  Scene s;
  s.mode = hermite::SceneMode::HoleFill;
  s.data.preset = "torus";
  s.data.count = 250;
  s.fit.method = hermite::FitMethod::RbfOffset;
  s.fit.kernel = hermite::KernelType::Wendland;
  s.fit.radius = 0.37;
  s.fit.polynomial = hermite::Polynomial::Quadratic;
  s.fit.smoothing = 1e-6;
  s.fit.shift = 0.025;
  s.fit.solver = hermite::SolverChoice::Ldlt;
  s.fit.partition = {hermite::PartitionSwitch::On, 35, 0.2, 1.25};
  s.transform.translate = {0.1, -0.2, 0.3};
  s.transform.rotateAxisAngleDeg = {1, 2, 3, 33.3};
  s.transform.scale = 1.7;
  s.view.size = {640, 480};
  s.view.background = {0.1, 0.2, 0.3};
  s.view.bounds = std::vector<double>{-1, -2, -3, 1, 2, 3};
  s.view.projection = hermite::Projection::Orthographic;
  s.view.camera = {{1, 2, 3}, {0.5, 0, 0}, {0, 0, 1}, 55};
  s.view.center2d = {0.25, -0.5};
  s.view.halfHeight2d = 3.0;
  s.view.showPoints = false;
  s.view.showNormals = false;
  s.view.showBounds = true;
  s.view.showAxes = true;
  s.view.trace = hermite::TraceMode::Exact;
  s.view.slice = {true, {1, 1, 0}, -0.3};
  s.sourceName = "x.json";
  return s;
}

}  // namespace

TEST_CASE("scene: minimal scene takes the documented defaults") {
  const Scene s = parse(scene3d());
  CHECK(s.version == 1);
  CHECK(s.mode == hermite::SceneMode::Implicit3d);
  CHECK(s.dimension() == 3);
  CHECK(s.data.preset == "sphere6");
  CHECK(s.data.count == 0);
  CHECK(s.fit.method == hermite::FitMethod::Hrbf);
  CHECK(s.fit.kernel == hermite::KernelType::Cubic);
  CHECK(s.fit.radius == 1.0);
  CHECK(s.fit.polynomial == hermite::Polynomial::Linear);
  CHECK(s.fit.smoothing == 0.0);
  CHECK(s.fit.shift == 0.01);
  CHECK(s.fit.solver == hermite::SolverChoice::Auto);
  CHECK(s.fit.partition == hermite::PartitionSpec{hermite::PartitionSwitch::Auto, 20, 0.0, 1.5});
  CHECK(s.transform.translate == std::vector<double>{0, 0, 0});
  CHECK(s.transform.isIdentity());
  CHECK(s.view.size == std::array<int, 2>{800, 600});
  CHECK(!s.view.bounds.has_value());
  CHECK(s.view.camera.eye == std::array<double, 3>{0, 0, 4});
  CHECK(s.view.camera.fovYDeg == 40.0);
  CHECK(s.view.halfHeight2d == 1.5);
  CHECK(s.view.trace == hermite::TraceMode::Auto);
  CHECK(!s.view.showNormals.has_value());  // "auto"
  CHECK(s.view.normalsShown(hermite::kAutoNormalsMaxSamples));
  CHECK(!s.view.normalsShown(hermite::kAutoNormalsMaxSamples + 1));
  CHECK(hermite::sceneToJson(s)["view"]["show_normals"] == "auto");
  CHECK(parse(scene3d(R"("view": {"show_normals": "auto"})")).view.showNormals == std::nullopt);
  CHECK(parse(scene3d(R"("view": {"show_normals": true})")).view.normalsShown(100000));
  CHECK(!parse(scene3d(R"("view": {"show_normals": false})")).view.normalsShown(1));
  CHECK(!s.view.presenter);
  CHECK(parse(scene3d(R"("view": {"presenter": true})")).view.presenter);
  CHECK(s.sourceName == "x.json");

  const Scene s2 = parse(scene2d());
  CHECK(s2.dimension() == 2);
  CHECK(s2.transform.translate == std::vector<double>{0, 0});
}

TEST_CASE("scene: the commented example of docs/scene-format.md equals the defaults") {
  const Scene example = hermite::loadSceneFile(kFixtures + "/scenes/commented.json");
  Scene minimal = hermite::loadSceneFile(kFixtures + "/scenes/minimal.json");
  minimal.sourceName = example.sourceName;
  CHECK(example == minimal);
}

TEST_CASE("scene: top-level structure errors") {
  CHECK(errorOf("[1, 2]") == "x.json: the scene must be a JSON object (got an array of 2 elements)");
  CHECK(errorOf(R"({"mode": "implicit3d", "data": {"preset": "a"}})") ==
        "x.json: version: missing (required; this program reads scene version 1)");
  CHECK(startsWith(errorOf(R"({"version": 1, "data": {"preset": "a"}})"), "x.json: mode: missing"));
  CHECK(startsWith(errorOf(R"({"version": 1, "mode": "implicit3d"})"), "x.json: data: missing"));
  CHECK(errorOf(R"({"version": 2, "mode": "implicit3d", "data": {"preset": "a"}})") ==
        "x.json: version: unsupported scene version 2 (this program reads version 1)");
  CHECK(errorOf(R"({"version": "1", "mode": "implicit3d", "data": {"preset": "a"}})") ==
        "x.json: version: must be an integer (got string \"1\")");
  CHECK(errorOf(R"({"version": 1.0, "mode": "implicit3d", "data": {"preset": "a"}})") == "<no error>");
  CHECK(errorOf(R"({"version": 1e10, "mode": "implicit3d", "data": {"preset": "a"}})") ==
        "x.json: version: must be an integer in the 32-bit range (got 1e+10)");
  CHECK(errorOf(R"({"version": 1, "mode": "implicit4d", "data": {"preset": "a"}})") ==
        "x.json: mode: must be one of: implicit2d, implicit3d, patch, holefill (got string \"implicit4d\")");
  CHECK(errorOf(scene3d(R"("colour": 1)")) ==
        "x.json: colour: unknown key (expected one of: version, mode, data, fit, transform, view, patch, holefill)");
  CHECK(errorOf(scene3d(R"("fit": 3)")) == "x.json: fit: must be an object (got 3)");
}

TEST_CASE("scene: unknown keys name the full path and suggest the closest key") {
  CHECK(errorOf(scene3d(R"("fit": {"kernl": "cubic"})")) ==
        "x.json: fit.kernl: unknown key (expected one of: method, kernel, radius, polynomial, "
        "smoothing, shift, solver, partition, reach_mask); did you mean 'kernel'?");
  CHECK(startsWith(errorOf(scene3d(R"("fit": {"partition": {"overlapp": 2}})")),
                   "x.json: fit.partition.overlapp: unknown key (expected one of: enabled, "));
  CHECK(startsWith(errorOf(scene3d(R"("view": {"camera": {"fov": 30}})")),
                   "x.json: view.camera.fov: unknown key"));
  CHECK(startsWith(errorOf(scene3d(R"("view": {"slice": {"enable": true}})")),
                   "x.json: view.slice.enable: unknown key"));
  CHECK(startsWith(errorOf(scene3d(R"("view": {"view2d": {"halfheight": 1}})")),
                   "x.json: view.view2d.halfheight: unknown key"));
  CHECK(startsWith(errorOf(scene3d(R"("transform": {"rotate": 1})")), "x.json: transform.rotate: unknown key"));
  CHECK(startsWith(errorOf(R"({"version": 1, "mode": "implicit3d", "data": {"preset": "a", "counts": 3}})"),
                   "x.json: data.counts: unknown key"));
  // No suggestion when nothing is close.
  CHECK(errorOf(scene3d(R"("fit": {"zzzzzzzz": 1})")).find("did you mean") == std::string::npos);
}

TEST_CASE("scene: data sources") {
  SUBCASE("preset with count") {
    const Scene s = parse(R"({"version": 1, "mode": "implicit3d", "data": {"preset": "bunny", "count": 500.0}})");
    CHECK(s.data.preset == "bunny");
    CHECK(s.data.count == 500);
    CHECK(!s.data.isInline());
  }
  SUBCASE("preset names are not checked here") {
    CHECK(errorOf(R"({"version": 1, "mode": "implicit3d", "data": {"preset": "no-such-preset"}})") ==
          "<no error>");
  }
  SUBCASE("file paths are resolved against the base directory; absolute paths are kept") {
    const Scene s = parse(R"({"version": 1, "mode": "implicit3d", "data": {"file": "pts/a.xyz"}})");
    CHECK(s.data.file == "pts/a.xyz");
    CHECK(s.data.resolvedFile == "/base/dir/pts/a.xyz");
    const Scene a = parse(R"({"version": 1, "mode": "implicit3d", "data": {"file": "/abs/b.xyz"}})");
    CHECK(a.data.resolvedFile == "/abs/b.xyz");
  }
  SUBCASE("inline data of the scene's dimension") {
    const Scene s = parse(R"({"version": 1, "mode": "implicit2d",
        "data": {"points": [[0, 1], [2, 3.5]], "normals": [[0, 1], [1, 0]]}})");
    CHECK(s.data.isInline());
    CHECK(s.data.points == std::vector<std::vector<double>>{{0, 1}, {2, 3.5}});
    CHECK(s.data.normals == std::vector<std::vector<double>>{{0, 1}, {1, 0}});
  }
  const std::string head = R"({"version": 1, "mode": "implicit3d", "data": )";
  const std::string head2d = R"({"version": 1, "mode": "implicit2d", "data": )";
  CHECK(startsWith(errorOf(head + "{}}"), "x.json: data: no data source (expected one of"));
  CHECK(startsWith(errorOf(head + R"({"preset": "a", "file": "b.xyz"}})"),
                   "x.json: data: give exactly one data source, found data.preset and data.file"));
  CHECK(startsWith(errorOf(head + R"({"preset": "a", "points": [], "normals": []}})"),
                   "x.json: data: give exactly one data source, found data.preset and data.points"));
  CHECK(startsWith(errorOf(head + R"({"file": "a.xyz", "normals": []}})"),
                   "x.json: data: give exactly one data source, found data.file and data.normals"));
  CHECK(errorOf(head + R"({"file": "a.xyz", "count": 3}})") ==
        "x.json: data.count: only allowed together with data.preset");
  CHECK(errorOf(head + R"({"preset": "a", "orient_normals": false}})") ==
        "x.json: data.orient_normals: only allowed together with data.file (it says what happens to a file's normals)");
  CHECK(errorOf(head + R"({"file": "a.xyz", "orient_normals": "yes"}})") ==
        "x.json: data.orient_normals: must be \"auto\", true or false (got string \"yes\")");
  CHECK(parse(head + R"({"file": "a.xyz", "orient_normals": false}})").data.orientNormals == hermite::GivenNormals::Never);
  CHECK(parse(head + R"({"file": "a.xyz", "orient_normals": true}})").data.orientNormals == hermite::GivenNormals::Always);
  CHECK(parse(head + R"({"file": "a.xyz"}})").data.orientNormals == hermite::GivenNormals::Auto);
  CHECK(errorOf(head + R"({"preset": "a", "count": 2.5}})") == "x.json: data.count: must be an integer (got 2.5)");
  CHECK(errorOf(head + R"({"preset": "a", "count": -1}})") == "x.json: data.count: must be >= 0 (got -1)");
  CHECK(errorOf(head + R"({"preset": "a", "count": "many"}})") ==
        "x.json: data.count: must be an integer (got string \"many\")");
  CHECK(errorOf(head + R"({"preset": 3}})") == "x.json: data.preset: must be a string (got 3)");
  CHECK(errorOf(head + R"({"preset": ""}})") == "x.json: data.preset: must be a non-empty preset name");
  CHECK(errorOf(head + R"({"file": ""}})") == "x.json: data.file: must be a non-empty path");
  CHECK(errorOf(head + R"({"file": ["a"]}})") == "x.json: data.file: must be a string (got an array of 1 elements)");
  CHECK(errorOf(head + R"({"points": [[0, 0, 0]]}})") ==
        "x.json: data.normals: missing: inline data needs both data.points and data.normals");
  CHECK(errorOf(head + R"({"normals": [[0, 0, 1]]}})") ==
        "x.json: data.points: missing: inline data needs both data.points and data.normals");
  CHECK(errorOf(head2d + R"({"points": [[0, 0], [1, 0, 0]], "normals": [[0, 1], [0, 1]]}})") ==
        "x.json: data.points[1]: must be an array of 2 numbers (2D scene) (got an array of 3 elements)");
  CHECK(errorOf(head + R"({"points": [[0, 0]], "normals": [[0, 1]]}})") ==
        "x.json: data.points[0]: must be an array of 3 numbers (3D scene) (got an array of 2 elements)");
  CHECK(errorOf(head + R"({"points": [[0, 0, 0]], "normals": [[0, "up", 1]]}})") ==
        "x.json: data.normals[0][1]: must be a number (got string \"up\")");
  CHECK(errorOf(head + R"({"points": [[0, 0, 0], [1, 1, 1]], "normals": [[0, 0, 1]]}})") ==
        "x.json: data.normals: has 1 entries but data.points has 2 (one normal per point)");
  CHECK(errorOf(head + R"({"points": {"x": 1}, "normals": []}})") ==
        "x.json: data.points: must be an array of [x, y, z] entries (got an object)");
}

TEST_CASE("scene: fit validation") {
  CHECK(errorOf(scene3d(R"("fit": {"radius": -1})")) == "x.json: fit.radius: must be > 0 (got -1)");
  CHECK(errorOf(scene3d(R"("fit": {"radius": 0})")) == "x.json: fit.radius: must be > 0 (got 0)");
  CHECK(errorOf(scene3d(R"("fit": {"radius": "1"})")) == "x.json: fit.radius: must be a number (got string \"1\")");
  CHECK(errorOf(scene3d(R"("fit": {"method": "rbf"})")) ==
        "x.json: fit.method: must be one of: hrbf, rbf-offset (got string \"rbf\")");
  // The kernel parser's own message, prefixed with the key path.
  const std::string kernel = errorOf(scene3d(R"("fit": {"kernel": "gauss"})"));
  CHECK(startsWith(kernel, "x.json: fit.kernel: "));
  CHECK(kernel.find("gauss") != std::string::npos);
  CHECK(kernel.find("wendland") != std::string::npos);
  CHECK(startsWith(errorOf(scene3d(R"("fit": {"kernel": "thin-plate"})")), "x.json: fit.kernel: "));
  CHECK(errorOf(scene3d(R"("fit": {"kernel": 3})")) == "x.json: fit.kernel: must be a string (got 3)");
  const std::string poly = errorOf(scene3d(R"("fit": {"polynomial": "cubic"})"));
  CHECK(startsWith(poly, "x.json: fit.polynomial: "));
  CHECK(poly.find("quadratic") != std::string::npos);
  const std::string solver = errorOf(scene3d(R"("fit": {"solver": "qr"})"));
  CHECK(startsWith(solver, "x.json: fit.solver: "));
  CHECK(solver.find("nullspace-cholesky") != std::string::npos);
  CHECK(errorOf(scene3d(R"("fit": {"smoothing": -0.1})")) == "x.json: fit.smoothing: must be >= 0 (got -0.1)");
  CHECK(errorOf(scene3d(R"("fit": {"shift": 0})")) == "x.json: fit.shift: must be > 0 (got 0)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"enabled": "true"}})")) ==
        "x.json: fit.partition.enabled: must be \"auto\", true or false (got string \"true\")");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"max_points_per_box": 0}})")) ==
        "x.json: fit.partition.max_points_per_box: must be >= 1 (got 0)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"max_points_per_box": 2.5}})")) ==
        "x.json: fit.partition.max_points_per_box: must be an integer (got 2.5)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"max_points_per_box": 1e20}})")) ==
        "x.json: fit.partition.max_points_per_box: must be >= 1 (got 1e+20)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"box_size": -1}})")) ==
        "x.json: fit.partition.box_size: must be >= 0 (got -1)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"overlap": 0.5}})")) ==
        "x.json: fit.partition.overlap: must be >= 1 (got 0.5)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": []})")) ==
        "x.json: fit.partition: must be an object (got an array of 0 elements)");

  const Scene s = parse(scene3d(R"("fit": {"method": "rbf-offset", "kernel": "gaussian", "radius": 0.5,
      "polynomial": "none", "smoothing": 0.001, "shift": 0.05, "solver": "cholesky",
      "partition": {"enabled": true, "max_points_per_box": 8.0, "box_size": 0.25, "overlap": 1}})"));
  CHECK(s.fit.method == hermite::FitMethod::RbfOffset);
  CHECK(s.fit.kernel == hermite::KernelType::Gaussian);
  CHECK(s.fit.radius == 0.5);
  CHECK(s.fit.polynomial == hermite::Polynomial::None);
  CHECK(s.fit.smoothing == 0.001);
  CHECK(s.fit.shift == 0.05);
  CHECK(s.fit.solver == hermite::SolverChoice::Cholesky);
  CHECK(s.fit.partition == hermite::PartitionSpec{hermite::PartitionSwitch::On, 8, 0.25, 1.0});

  // Added key fit.partition.blend: smooth (default) | hard.
  CHECK(parse(scene3d(R"("fit": {"partition": {"blend": "hard"}})")).fit.partition.blend == hermite::PuBlend::Hard);
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"blend": "soft"}})")) ==
        "x.json: fit.partition.blend: unknown blend 'soft' (expected smooth or hard)");
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"blend": 1}})")) ==
        "x.json: fit.partition.blend: must be a string (got 1)");
  // Added key fit.partition.data_reach: > 0, default 3.
  CHECK(parse(scene3d(R"("fit": {})")).fit.partition.dataReach == 3.0);
  CHECK(parse(scene3d(R"("fit": {"partition": {"data_reach": 2.5}})")).fit.partition.dataReach == 2.5);
  CHECK(errorOf(scene3d(R"("fit": {"partition": {"data_reach": 0}})")) ==
        "x.json: fit.partition.data_reach: must be > 0 (got 0)");
}

TEST_CASE("scene: fixture with an out-of-range radius names the file and key") {
  const std::string path = kFixtures + "/scenes/bad_radius.json";
  CHECK_THROWS_WITH_AS(hermite::loadSceneFile(path), (path + ": fit.radius: must be > 0 (got -1)").c_str(),
                       InputError);
}

TEST_CASE("scene: transform validation in 3D and 2D") {
  CHECK(errorOf(scene3d(R"("transform": {"translate": [1, 2]})")) ==
        "x.json: transform.translate: must be an array of 3 numbers [x, y, z] in a 3D scene (got an array "
        "of 2 elements)");
  CHECK(errorOf(scene3d(R"("transform": {"rotate_axis_angle_deg": [0, 0, 0, 30]})")) ==
        "x.json: transform.rotate_axis_angle_deg: the axis (first three numbers) must be non-zero");
  CHECK(startsWith(errorOf(scene3d(R"("transform": {"rotate_axis_angle_deg": [0, 0, 1]})")),
                   "x.json: transform.rotate_axis_angle_deg: must be an array of 4 numbers [ax, ay, az, degrees]"));
  CHECK(errorOf(scene3d(R"("transform": {"scale": 0})")) == "x.json: transform.scale: must be > 0 (got 0)");
  CHECK(errorOf(scene3d(R"("transform": {"scale": -2})")) == "x.json: transform.scale: must be > 0 (got -2)");
  CHECK(errorOf(scene3d(R"("transform": {"rotate_deg": 30})")) ==
        "x.json: transform.rotate_deg: only for 2D scenes (mode implicit2d); use "
        "transform.rotate_axis_angle_deg [ax, ay, az, degrees] in a 3D scene");
  CHECK(errorOf(scene2d(R"("transform": {"rotate_axis_angle_deg": [0, 0, 1, 30]})")) ==
        "x.json: transform.rotate_axis_angle_deg: not available in a 2D scene (mode implicit2d); use "
        "transform.rotate_deg (one angle in degrees, counter-clockwise)");
  CHECK(startsWith(errorOf(scene2d(R"("transform": {"translate": [1, 2, 3]})")),
                   "x.json: transform.translate: must be an array of 2 numbers [x, y] in a 2D scene"));
  CHECK(errorOf(scene2d(R"("transform": {"rotate_deg": [30]})")) ==
        "x.json: transform.rotate_deg: must be a number (got an array of 1 elements)");

  const Scene s3 = parse(scene3d(R"("transform": {"translate": [1, 2, 3], "rotate_axis_angle_deg": [0, 1, 0, 90],
      "scale": 2})"));
  CHECK(s3.transform.translate == std::vector<double>{1, 2, 3});
  CHECK(s3.transform.rotateAxisAngleDeg == std::array<double, 4>{0, 1, 0, 90});
  CHECK(s3.transform.scale == 2);
  CHECK(!s3.transform.isIdentity());
  const Scene s2 = parse(scene2d(R"("transform": {"translate": [1, 2], "rotate_deg": 45})"));
  CHECK(s2.transform.translate == std::vector<double>{1, 2});
  CHECK(s2.transform.rotateDeg == 45);
  CHECK(!s2.transform.isIdentity());
}

TEST_CASE("scene: TransformSpec::isIdentity") {
  hermite::TransformSpec t;
  CHECK(t.isIdentity());
  t.translate = {0, 0, 0};
  CHECK(t.isIdentity());
  t.rotateAxisAngleDeg = {1, 0, 0, 360};  // a whole turn
  CHECK(t.isIdentity());
  t.rotateAxisAngleDeg = {1, 0, 0, 1e-9};
  CHECK(!t.isIdentity());
  t.rotateAxisAngleDeg = {1, 0, 0, 0};
  t.translate = {0, 1e-300, 0};
  CHECK(!t.isIdentity());
  t.translate = {0, 0};
  t.rotateDeg = -720;
  CHECK(t.isIdentity());
  t.rotateDeg = 90;
  CHECK(!t.isIdentity());
  t.rotateDeg = 0;
  t.scale = 1.5;
  CHECK(!t.isIdentity());
}

TEST_CASE("scene: view validation") {
  CHECK(errorOf(scene3d(R"("view": {"size": [0, 10]})")) ==
        "x.json: view.size[0]: must be between 1 and 16384 (got 0)");
  CHECK(errorOf(scene3d(R"("view": {"size": [10, 16385]})")) ==
        "x.json: view.size[1]: must be between 1 and 16384 (got 16385)");
  CHECK(errorOf(scene3d(R"("view": {"size": [640.5, 480]})")) ==
        "x.json: view.size[0]: must be an integer (got 640.5)");
  CHECK(errorOf(scene3d(R"("view": {"size": [640]})")) ==
        "x.json: view.size: must be an array of 2 integers [width, height] (got an array of 1 elements)");
  CHECK(parse(scene3d(R"("view": {"size": [640.0, 480]})")).view.size == std::array<int, 2>{640, 480});
  CHECK(errorOf(scene3d(R"("view": {"background": [1.5, 0, 0]})")) ==
        "x.json: view.background[0]: must be in [0, 1] (got 1.5)");
  CHECK(errorOf(scene3d(R"("view": {"background": [0, 0, -0.1]})")) ==
        "x.json: view.background[2]: must be in [0, 1] (got -0.1)");
  CHECK(startsWith(errorOf(scene3d(R"("view": {"bounds": [0, 0, 1, 1]})")),
                   "x.json: view.bounds: must be an array of 6 numbers [xmin, ymin, zmin, xmax, ymax, zmax] or "
                   "null in a 3D scene"));
  CHECK(startsWith(errorOf(scene2d(R"("view": {"bounds": [0, 0, 0, 1, 1, 1]})")),
                   "x.json: view.bounds: must be an array of 4 numbers [xmin, ymin, xmax, ymax] or null in a 2D "
                   "scene"));
  CHECK(errorOf(scene3d(R"("view": {"bounds": [0, 1, 0, 1, 1, 1]})")) ==
        "x.json: view.bounds: min must be < max on every axis; on y min is 1 and max is 1");
  CHECK(errorOf(scene2d(R"("view": {"bounds": [3, 0, 1, 1]})")) ==
        "x.json: view.bounds: min must be < max on every axis; on x min is 3 and max is 1");
  CHECK(parse(scene3d(R"("view": {"bounds": null})")).view.bounds == std::nullopt);
  CHECK(parse(scene2d(R"("view": {"bounds": [-1, -2, 1, 2]})")).view.bounds == std::vector<double>{-1, -2, 1, 2});
  CHECK(errorOf(scene3d(R"("view": {"projection": "fisheye"})")) ==
        "x.json: view.projection: must be one of: perspective, orthographic (got string \"fisheye\")");
  CHECK(errorOf(scene3d(R"("view": {"camera": {"eye": [1, 1, 1], "target": [1, 1, 1]}})")) ==
        "x.json: view.camera.target: must differ from view.camera.eye (the view direction is target - eye)");
  CHECK(errorOf(scene3d(R"("view": {"camera": {"eye": [0, 3, 0], "target": [0, 0, 0]}})")) ==
        "x.json: view.camera.up: must be non-zero and not parallel to the view direction target - eye");
  CHECK(errorOf(scene3d(R"("view": {"camera": {"up": [0, 0, 0]}})")) ==
        "x.json: view.camera.up: must be non-zero and not parallel to the view direction target - eye");
  CHECK(startsWith(errorOf(scene3d(R"("view": {"camera": {"eye": [0, 0]}})")),
                   "x.json: view.camera.eye: must be an array of 3 numbers [x, y, z]"));
  CHECK(errorOf(scene3d(R"("view": {"camera": {"fov_y_deg": 0}})")) ==
        "x.json: view.camera.fov_y_deg: must be in (0, 180) degrees (got 0)");
  CHECK(errorOf(scene3d(R"("view": {"camera": {"fov_y_deg": 180}})")) ==
        "x.json: view.camera.fov_y_deg: must be in (0, 180) degrees (got 180)");
  CHECK(errorOf(scene3d(R"("view": {"view2d": {"half_height": 0}})")) ==
        "x.json: view.view2d.half_height: must be > 0 (got 0)");
  CHECK(startsWith(errorOf(scene3d(R"("view": {"view2d": {"center": [0, 0, 0]}})")),
                   "x.json: view.view2d.center: must be an array of 2 numbers [x, y]"));
  CHECK(errorOf(scene3d(R"("view": {"show_points": "yes"})")) ==
        "x.json: view.show_points: must be true or false (got string \"yes\")");
  CHECK(errorOf(scene3d(R"("view": {"show_normals": 1})")) ==
        "x.json: view.show_normals: must be true, false or \"auto\" (got 1)");
  CHECK(errorOf(scene3d(R"("view": {"show_normals": "yes"})")) ==
        "x.json: view.show_normals: must be true, false or \"auto\" (got string \"yes\")");
  CHECK(errorOf(scene3d(R"("view": {"show_bounds": null})")) ==
        "x.json: view.show_bounds: must be true or false (got null)");
  CHECK(errorOf(scene3d(R"("view": {"presenter": "on"})")) ==
        "x.json: view.presenter: must be true or false (got string \"on\")");
  CHECK(errorOf(scene3d(R"("view": {"trace": "fast"})")) ==
        "x.json: view.trace: must be one of: auto, baked, exact (got string \"fast\")");
  CHECK(errorOf(scene3d(R"("view": {"slice": {"normal": [0, 0, 0]}})")) ==
        "x.json: view.slice.normal: must be non-zero");
  CHECK(errorOf(scene3d(R"("view": {"slice": {"enabled": 1}})")) ==
        "x.json: view.slice.enabled: must be true or false (got 1)");
  CHECK(errorOf(scene3d(R"("view": {"slice": {"offset": "0"}})")) ==
        "x.json: view.slice.offset: must be a number (got string \"0\")");
}

TEST_CASE("scene: non-finite numbers built in memory are rejected") {
  json doc = json::parse(scene3d());
  doc["fit"]["radius"] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH_AS(hermite::parseScene(doc, "m", ""), "m: fit.radius: must be a finite number (got inf)",
                       InputError);
  doc = json::parse(scene3d());
  doc["view"]["camera"]["eye"] = {0, std::nan(""), 1};
  CHECK_THROWS_WITH_AS(hermite::parseScene(doc, "m", ""), "m: view.camera.eye[1]: must be a finite number (got nan)",
                       InputError);
}

TEST_CASE("scene: sceneToJson writes every key and parseScene reproduces the scene") {
  SUBCASE("3D, every field non-default") {
    const Scene s = nonDefaultScene3d();
    const json doc = hermite::sceneToJson(s);
    CHECK(hermite::parseScene(doc, "x.json", "") == s);
    // Through text as well: doubles are written so they read back exactly.
    CHECK(hermite::parseScene(json::parse(doc.dump()), "x.json", "") == s);
    for (const char* key : {"version", "mode", "data", "fit", "transform", "view"}) CHECK(doc.contains(key));
    for (const char* key : {"method", "kernel", "radius", "polynomial", "smoothing", "shift", "solver", "partition"})
      CHECK(doc["fit"].contains(key));
    for (const char* key : {"enabled", "max_points_per_box", "box_size", "overlap"})
      CHECK(doc["fit"]["partition"].contains(key));
    for (const char* key : {"translate", "rotate_axis_angle_deg", "scale"}) CHECK(doc["transform"].contains(key));
    CHECK(!doc["transform"].contains("rotate_deg"));
    for (const char* key : {"size", "background", "bounds", "projection", "camera", "view2d", "show_points",
                            "show_normals", "show_bounds", "show_axes", "presenter", "trace", "slice"})
      CHECK(doc["view"].contains(key));
    CHECK(doc["view"]["view2d"].contains("center"));
    CHECK(doc["view"]["view2d"].contains("half_height"));
    CHECK(doc["view"]["camera"].contains("fov_y_deg"));
    CHECK(doc["fit"]["kernel"] == "wendland");
    CHECK(doc["fit"]["method"] == "rbf-offset");
    CHECK(doc["fit"]["solver"] == "ldlt");
    CHECK(doc["view"]["trace"] == "exact");
    CHECK(doc["view"]["projection"] == "orthographic");
    CHECK(doc["mode"] == "holefill");
    CHECK(doc["data"] == json{{"preset", "torus"}, {"count", 250}});
  }
  SUBCASE("defaults: the minimal scene expands to the documented document") {
    const Scene s = parse(scene3d());
    const json doc = hermite::sceneToJson(s);
    CHECK(hermite::parseScene(doc, "x.json", "/base/dir") == s);
    CHECK(doc["view"]["bounds"].is_null());
    CHECK(doc["data"] == json{{"preset", "sphere6"}, {"count", 0}});
    CHECK(doc["fit"]["partition"]["max_points_per_box"] == 20);
    CHECK(doc["transform"]["rotate_axis_angle_deg"] == json{0.0, 0.0, 1.0, 0.0});
    CHECK(doc["view"]["size"] == json{800, 600});
  }
  SUBCASE("2D with inline data and a file source") {
    Scene s = hermite::loadSceneFile(kFixtures + "/scenes/square_2d.json");
    CHECK(s.dimension() == 2);
    CHECK(s.data.points.size() == 4);
    const json doc = hermite::sceneToJson(s);
    CHECK(doc["transform"].contains("rotate_deg"));
    CHECK(!doc["transform"].contains("rotate_axis_angle_deg"));
    CHECK(doc["transform"]["translate"] == json{0.5, -0.25});
    CHECK(hermite::parseScene(doc, s.sourceName, "") == s);

    const Scene f = parse(R"({"version": 1, "mode": "patch", "data": {"file": "pts/a.xyz"}})");
    const json fdoc = hermite::sceneToJson(f);
    CHECK(fdoc["data"] == json{{"file", "pts/a.xyz"}});
    CHECK(hermite::parseScene(fdoc, "x.json", "/base/dir") == f);
  }
}

TEST_CASE("scene: --set overrides") {
  json doc = json::parse(scene3d(R"("fit": {"kernel": "gaussian"})"));
  hermite::applySetOverride(doc, "fit.kernel=cubic");  // not JSON: taken as a string
  CHECK(doc["fit"]["kernel"] == "cubic");
  hermite::applySetOverride(doc, "fit.radius=0.5");
  CHECK(doc["fit"]["radius"].is_number_float());
  CHECK(doc["fit"]["radius"] == 0.5);
  hermite::applySetOverride(doc, "view.size=[640,480]");  // creates "view"
  CHECK(doc["view"]["size"] == json{640, 480});
  hermite::applySetOverride(doc, "view.camera.fov_y_deg=30");  // nested creation
  CHECK(doc["view"]["camera"]["fov_y_deg"] == 30);
  hermite::applySetOverride(doc, "fit.partition.enabled=true");
  CHECK(doc["fit"]["partition"]["enabled"] == true);
  hermite::applySetOverride(doc, "view.bounds=null");
  CHECK(doc["view"]["bounds"].is_null());
  hermite::applySetOverride(doc, "data.preset=\"42\"");  // a JSON string stays a string
  CHECK(doc["data"]["preset"] == "42");
  hermite::applySetOverride(doc, "data.preset=a=b");  // only the first '=' separates
  CHECK(doc["data"]["preset"] == "a=b");
  hermite::applySetOverride(doc, "view.camera={\"eye\": [0, 0, 9]}");
  CHECK(doc["view"]["camera"] == json{{"eye", {0, 0, 9}}});

  const Scene s = hermite::parseScene(doc, "x.json", "");
  CHECK(s.fit.kernel == hermite::KernelType::Cubic);
  CHECK(s.fit.radius == 0.5);
  CHECK(s.view.size == std::array<int, 2>{640, 480});
  CHECK(s.view.camera.eye == std::array<double, 3>{0, 0, 9});
  CHECK(s.fit.partition.enabled == hermite::PartitionSwitch::On);

  CHECK_THROWS_WITH_AS(hermite::applySetOverride(doc, "fit.radius.value=1"),
                       "--set fit.radius.value: fit.radius is not an object (it is 0.5), so it cannot hold 'value'",
                       InputError);
  CHECK_THROWS_WITH_AS(hermite::applySetOverride(doc, "view.size.width=3"),
                       "--set view.size.width: view.size is not an object (it is an array of 2 elements), so it "
                       "cannot hold 'width'",
                       InputError);
  CHECK_THROWS_AS(hermite::applySetOverride(doc, "fit.radius"), hermite::UsageError);
  CHECK_THROWS_AS(hermite::applySetOverride(doc, "=3"), hermite::UsageError);
  CHECK_THROWS_AS(hermite::applySetOverride(doc, "fit..radius=3"), hermite::UsageError);
  CHECK_THROWS_AS(hermite::applySetOverride(doc, "fit.=3"), hermite::UsageError);
  CHECK_THROWS_WITH_AS(hermite::applySetOverride(doc, "fit.radius"),
                       "--set 'fit.radius': expected KEY=VALUE (e.g. fit.kernel=cubic)", hermite::UsageError);
  // An override that makes the scene invalid is reported by the strict parse.
  hermite::applySetOverride(doc, "fit.kernl=cubic");
  CHECK(startsWith(
      [&] {
        try {
          hermite::parseScene(doc, "x.json", "");
        } catch (const InputError& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      "x.json: fit.kernl: unknown key"));
}

TEST_CASE("scene: loadSceneFile applies overrides and resolves data files") {
  const std::string path = kFixtures + "/scenes/file_data.json";
  const Scene s = hermite::loadSceneFile(path, {"fit.kernel=gaussian", "fit.radius=0.25"});
  CHECK(s.sourceName == path);
  CHECK(s.fit.kernel == hermite::KernelType::Gaussian);
  CHECK(s.fit.radius == 0.25);
  CHECK(s.data.file == "../points/tetra.xyzn");
  CHECK(fs::equivalent(s.data.resolvedFile, kFixtures + "/points/tetra.xyzn"));
  // Overrides are checked as strictly as the file itself.
  CHECK_THROWS_WITH_AS(hermite::loadSceneFile(path, {"fit.radius=-1"}),
                       (path + ": fit.radius: must be > 0 (got -1)").c_str(), InputError);
  CHECK_THROWS_AS(hermite::loadSceneFile(path, {"noequals"}), hermite::UsageError);
}

TEST_CASE("scene: file errors carry the path, line and column") {
  SUBCASE("missing file") {
    const std::string path = kFixtures + "/scenes/does_not_exist.json";
    CHECK_THROWS_WITH_AS(hermite::loadSceneFile(path), (path + ": cannot open (No such file or directory)").c_str(),
                         InputError);
  }
  SUBCASE("a directory") {
    const std::string path = kFixtures + "/scenes";
    CHECK_THROWS_WITH_AS(hermite::loadSceneFile(path), (path + ": cannot open (it is a directory)").c_str(),
                         InputError);
  }
  SUBCASE("syntax error: line and column of the offending character") {
    const std::string path = kFixtures + "/scenes/syntax_error.json";
    std::string message;
    try {
      hermite::loadSceneFile(path);
    } catch (const InputError& e) {
      message = e.what();
    }
    // Line 5 is `  "fit": { "radius": 1.0, }`; the '}' after the trailing comma is column 27.
    CHECK(startsWith(message, path + ":5:27: JSON syntax error: "));
    CHECK(message.find("[json.exception") == std::string::npos);
  }
  SUBCASE("syntax error at the end of the file") {
    TempDir dir;
    const std::string path = dir.file("truncated.json");
    writeText(path, "{\n  \"version\": 1,\n  \"mode\": ");
    std::string message;
    try {
      hermite::loadSceneFile(path);
    } catch (const InputError& e) {
      message = e.what();
    }
    CHECK(startsWith(message, path + ":3:11: JSON syntax error: "));
  }
  SUBCASE("duplicate keys") {
    const std::string path = kFixtures + "/scenes/duplicate_key.json";
    CHECK_THROWS_WITH_AS(hermite::loadSceneFile(path),
                         (path + ": fit.radius: duplicate key (each key may appear once per object)").c_str(),
                         InputError);
  }
  SUBCASE("an empty file") {
    TempDir dir;
    const std::string path = dir.file("empty.json");
    writeText(path, "");
    std::string message;
    try {
      hermite::loadSceneFile(path);
    } catch (const InputError& e) {
      message = e.what();
    }
    CHECK(startsWith(message, path + ":1:1: JSON syntax error: "));
  }
}

TEST_CASE("scene: saveSceneFile writes atomically and round-trips") {
  TempDir dir;
  const std::string path = dir.file("scene.json");
  Scene s = nonDefaultScene3d();
  s.sourceName = path;
  hermite::saveSceneFile(s, path);
  CHECK(dir.entries() == std::vector<std::string>{"scene.json"});
  CHECK(hermite::loadSceneFile(path) == s);

  // Overwriting replaces the file completely.
  Scene small = parse(scene3d());
  small.sourceName = path;
  hermite::saveSceneFile(small, path);
  CHECK(hermite::loadSceneFile(path) == small);
  CHECK(dir.entries() == std::vector<std::string>{"scene.json"});
}

TEST_CASE("scene: saveSceneFile keeps the old file when writing fails") {
  TempDir dir;
  const std::string path = dir.file("scene.json");
  const std::string oldText = "old contents\n";
  writeText(path, oldText);

  // A large scene (inline data) so that the write itself can be made to fail.
  Scene big = parse(scene3d());
  big.data = {};
  for (int i = 0; i < 2000; ++i) {
    big.data.points.push_back({i * 0.001, 0.5, -0.25});
    big.data.normals.push_back({0, 0, 1});
  }

  SUBCASE("the write fails (file size limit)") {
    rlimit old{};
    REQUIRE(getrlimit(RLIMIT_FSIZE, &old) == 0);
    rlimit limited = old;
    limited.rlim_cur = 4096;
    const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);
    REQUIRE(setrlimit(RLIMIT_FSIZE, &limited) == 0);
    std::string message;
    bool threwEnvironmentError = false;
    try {
      hermite::saveSceneFile(big, path);
    } catch (const hermite::EnvironmentError& e) {
      threwEnvironmentError = true;
      message = e.what();
    }
    setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, previousHandler);
    CHECK(threwEnvironmentError);
    CHECK(startsWith(message, path + ": cannot write"));
    CHECK(readText(path) == oldText);
    CHECK(dir.entries() == std::vector<std::string>{"scene.json"});
  }
  SUBCASE("the directory does not exist") {
    const std::string missing = dir.file("no/such/dir/scene.json");
    CHECK_THROWS_AS(hermite::saveSceneFile(big, missing), hermite::EnvironmentError);
    CHECK(dir.entries() == std::vector<std::string>{"scene.json"});
  }
  SUBCASE("the rename fails (the target is a directory)") {
    const std::string target = dir.file("taken");
    fs::create_directory(target);
    writeText(target + "/inside.txt", "x");
    CHECK_THROWS_AS(hermite::saveSceneFile(big, target), hermite::EnvironmentError);
    CHECK(fs::is_directory(target));
    CHECK(readText(target + "/inside.txt") == "x");
    CHECK(dir.entries() == std::vector<std::string>{"scene.json", "taken"});
  }
  SUBCASE("the directory is not writable") {
    if (::geteuid() == 0) {
      MESSAGE("running as root: permissions do not stop writes, skipped");
      return;
    }
    fs::permissions(dir.path, fs::perms::owner_read | fs::perms::owner_exec, fs::perm_options::replace);
    CHECK_THROWS_AS(hermite::saveSceneFile(big, path), hermite::EnvironmentError);
    fs::permissions(dir.path, fs::perms::owner_all, fs::perm_options::replace);
    CHECK(readText(path) == oldText);
    CHECK(dir.entries() == std::vector<std::string>{"scene.json"});
  }
}

TEST_CASE("scene: mode and method names") {
  CHECK(hermite::sceneModeName(hermite::SceneMode::Implicit2d) == "implicit2d");
  CHECK(hermite::sceneModeName(hermite::SceneMode::Implicit3d) == "implicit3d");
  CHECK(hermite::sceneModeName(hermite::SceneMode::Patch) == "patch");
  CHECK(hermite::sceneModeName(hermite::SceneMode::HoleFill) == "holefill");
  CHECK(hermite::fitMethodName(hermite::FitMethod::Hrbf) == "hrbf");
  CHECK(hermite::fitMethodName(hermite::FitMethod::RbfOffset) == "rbf-offset");
  CHECK(hermite::projectionName(hermite::Projection::Orthographic) == "orthographic");
  CHECK(hermite::traceModeName(hermite::TraceMode::Baked) == "baked");
}
