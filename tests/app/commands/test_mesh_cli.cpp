#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands/commands.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "core/shapes/analytic_shapes.h"
#include "io/mesh_file.h"
#include "support/cli_runner.h"
#include "support/mesh_test_shapes.h"

using hermite::testing::readAll;
using hermite::testing::runCli;
using hermite::testing::writeTemp;
using json = nlohmann::json;

namespace {

const char* kTorusScene =
    R"({"version": 1, "mode": "implicit3d", "data": {"preset": "torus", "count": 150},
        "fit": {"kernel": "cubic", "radius": 1.0, "polynomial": "linear"}})";
const char* kCurveScene =
    R"({"version": 1, "mode": "implicit2d", "data": {"preset": "curve2d", "count": 40},
        "fit": {"kernel": "cubic", "radius": 1.0, "polynomial": "linear"}})";

std::string tempPath(const std::string& name) { return writeTemp(name, ""); }

}  // namespace

TEST_CASE("mesh: a 3D scene becomes a closed manifold in every output format") {
  const std::string scene = writeTemp("mesh_torus.json", kTorusScene);
  for (const char* ext : {"obj", "ply", "glb", "gltf"}) {
    CAPTURE(ext);
    const std::string out = tempPath(std::string("torus_mesh.") + ext);
    std::filesystem::remove(out);
    const auto r = runCli("mesh " + scene + " -o " + out + " --resolution 40");
    REQUIRE(r.rc == 0);
    CHECK(r.out.find("closed manifold") != std::string::npos);
    const hermite::TriMesh mesh = hermite::loadMesh(out);
    const hermite::MeshCheck c = hermite::checkMesh(mesh);
    CHECK(c.closedManifold());
    CHECK(c.eulerCharacteristic == 0);  // the torus preset
    CHECK(hermite::signedVolume(mesh) > 0);
  }
}

TEST_CASE("mesh: a 2D scene becomes closed polylines, OBJ `l` elements or SVG paths") {
  const std::string scene = writeTemp("mesh_curve.json", kCurveScene);
  const std::string obj = tempPath("curve.obj"), svg = tempPath("curve.svg");
  auto r = runCli("mesh " + scene + " -o " + obj + " --resolution 80");
  REQUIRE(r.rc == 0);
  std::istringstream in(readAll(obj));
  std::string line;
  int vertices = 0, lines = 0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++vertices;
    if (line.rfind("l ", 0) == 0) {
      ++lines;
      // Closed: the element returns to its first vertex.
      std::istringstream ids(line.substr(2));
      std::vector<long> v;
      for (long id; ids >> id;) v.push_back(id);
      REQUIRE(v.size() >= 4);
      CHECK(v.front() == v.back());
      for (long id : v) CHECK((id >= 1 && id <= vertices));
    }
  }
  CHECK(vertices > 20);
  CHECK(lines >= 1);
  r = runCli("mesh " + scene + " -o " + svg + " --resolution 80");
  REQUIRE(r.rc == 0);
  const std::string text = readAll(svg);
  CHECK(text.rfind("<svg", 0) == 0);
  CHECK(text.find("<path d=\"M") != std::string::npos);
  CHECK(text.find("Z\"/>") != std::string::npos);
}

TEST_CASE("mesh: unknown extension is a usage error, an unwritable output exit 4, an old file survives") {
  const std::string scene = writeTemp("mesh_err.json", kTorusScene);
  auto r = runCli("mesh " + scene + " -o " + tempPath("out.stl"));
  CHECK(r.rc == 2);
  CHECK(r.err.find(".stl") != std::string::npos);
  CHECK(r.err.find(".glb") != std::string::npos);
  r = runCli("mesh " + writeTemp("mesh_err2d.json", kCurveScene) + " -o " + tempPath("out2d.ply"));
  CHECK(r.rc == 2);  // 2D scenes write .obj or .svg
  CHECK(r.err.find("(expected .obj, .svg): " + writeTemp("mesh_err2d.json", kCurveScene) + " is 2D data") !=
        std::string::npos);
  r = runCli("mesh " + scene + " -o /nonexistent-dir/out.obj");
  CHECK(r.rc == 4);
  CHECK(r.err.find("/nonexistent-dir") != std::string::npos);
  const std::string dir = tempPath("placeholder") + "_dir.obj";
  std::filesystem::create_directories(dir);
  r = runCli("mesh " + scene + " -o " + dir);
  CHECK(r.rc == 4);
  // A failing command leaves an existing output as it was.
  const std::string keep = writeTemp("keep.obj", "old contents\n");
  r = runCli("mesh " + scene + " -o " + keep + " --set fit.radius=-1");
  CHECK(r.rc == 1);
  CHECK(readAll(keep) == "old contents\n");
  r = runCli("mesh " + scene);  // -o is required
  CHECK(r.rc == 2);
  r = runCli("mesh " + scene + " -o " + tempPath("res.obj") + " --resolution 0");
  CHECK(r.rc == 2);
}

TEST_CASE("holefill: fills the holes of a mesh file and reports the docs/cli.md keys") {
  const hermite::SphereField sphere;
  hermite::Box<3> box;
  box.lo = hermite::Vec<3>::Constant(-1.3);
  box.hi = hermite::Vec<3>::Constant(1.3);
  hermite::TriMesh holed = hermite::marchingCubes(sphere, box, {40});
  holed.normals.resize(3, 0);
  holed = hermite::testing::cutBall(holed, Eigen::Vector3d(0, 0, 1), 0.3);
  holed = hermite::testing::cutBall(holed, Eigen::Vector3d(1, 0, 0), 0.25);
  const std::string in = tempPath("holed.ply"), out = tempPath("filled.obj");
  hermite::saveMesh(in, holed);

  auto r = runCli("holefill " + in + " -o " + out + " --json");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  for (const char* key : {"holes_found", "holes_filled", "triangles_added", "max_abs_f", "unconverged", "ms"})
    CHECK(j.contains(key));
  CHECK(j["holes_found"] == 2);
  CHECK(j["holes_filled"] == 2);
  CHECK(j["triangles_added"].get<int>() > 0);
  CHECK(j["max_abs_f"].get<double>() <= 1e-6);
  CHECK(j["unconverged"] == 0);
  const hermite::TriMesh filled = hermite::loadMesh(out);
  CHECK(hermite::checkMesh(filled).closedManifold());
  CHECK(filled.triangleCount() == holed.triangleCount() + j["triangles_added"].get<int>());

  r = runCli("holefill " + in + " -o " + out + " --implicit hrbf");
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("holes found:      2") != std::string::npos);
  CHECK(r.out.find("holes filled:     2") != std::string::npos);
}

TEST_CASE("holefill: each hole's method and result; exit 5 while a hole stays open unless --allow-open") {
  const hermite::SphereField sphere;
  hermite::Box<3> box;
  box.lo = hermite::Vec<3>::Constant(-1.3);
  box.hi = hermite::Vec<3>::Constant(1.3);
  hermite::TriMesh mesh = hermite::testing::cutBall(hermite::marchingCubes(sphere, box, {40}), Eigen::Vector3d(0, 0, 1), 0.3);
  mesh.normals.resize(3, 0);
  // A lone triangle beside the sphere: its rim is no hole to fill, so it stays open.
  const int v = mesh.vertexCount();
  mesh.vertices.conservativeResize(3, v + 3);
  mesh.vertices.col(v) = Eigen::Vector3d(3, 0, 0);
  mesh.vertices.col(v + 1) = Eigen::Vector3d(3.1, 0, 0);
  mesh.vertices.col(v + 2) = Eigen::Vector3d(3, 0.1, 0);
  mesh.triangles.conservativeResize(3, mesh.triangles.cols() + 1);
  mesh.triangles.col(mesh.triangles.cols() - 1) = Eigen::Vector3i(v, v + 1, v + 2);
  const std::string in = tempPath("open.ply"), out = tempPath("open_filled.ply");
  hermite::saveMesh(in, mesh);

  auto r = runCli("holefill " + in + " -o " + out + " --json");
  CHECK(r.rc == 5);
  CHECK(r.err.find("stay open") != std::string::npos);
  CHECK(std::filesystem::exists(out));  // written, though incomplete
  const json j = json::parse(r.out);
  CHECK(j["complete"] == false);
  REQUIRE(j["holes"].size() == 2);
  int filled = 0;
  for (const json& h : j["holes"]) {
    for (const char* key : {"edges", "method", "filled", "reason"}) CHECK(h.contains(key));
    if (h["filled"].get<bool>()) {
      ++filled;
      CHECK(h["reason"].is_null());
      CHECK((h["method"] == "front" || h["method"] == "min-weight"));
    } else {
      CHECK(h["edges"] == 3);
      CHECK(h["reason"].get<std::string>().find("lone triangle") != std::string::npos);
    }
  }
  CHECK(filled == 1);
  for (const char* key : {"welded_vertices", "collapsed_faces", "duplicate_faces", "reoriented_faces",
                          "non_manifold_edges", "non_orientable_components"})
    CHECK(j["repairs"][key] == 0);

  r = runCli("holefill " + in + " -o " + out + " --allow-open");
  CHECK(r.rc == 0);
  CHECK(r.out.find("open: it is the boundary of a lone triangle") != std::string::npos);
}

TEST_CASE("holefill: errors name the file and map to exit codes") {
  auto r = runCli("holefill /nonexistent/in.obj -o " + tempPath("x.obj"));
  CHECK(r.rc == 1);
  CHECK(r.err.find("/nonexistent/in.obj") != std::string::npos);
  const std::string garbage = writeTemp("garbage.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n");
  r = runCli("holefill " + garbage + " -o " + tempPath("y.obj"));
  CHECK(r.rc == 1);
  CHECK(r.err.find("garbage.off") != std::string::npos);
  r = runCli("holefill " + garbage + " -o " + tempPath("y.stl"));
  CHECK(r.rc == 2);
  r = runCli("holefill " + garbage + " -o /nonexistent-dir/y.obj");
  CHECK(r.rc == 4);
}

TEST_CASE("mesh --chord-tolerance: more triangles, still closed, the split edges in the summary; 0 turns it off, "
          "0.02 is the default; out of range exits 2") {
  const std::string scene = writeTemp("mesh_torus_chords.json", kTorusScene);
  const std::string plain = tempPath("torus_plain.ply"), refined = tempPath("torus_chords.ply");
  const std::string byDefault = tempPath("torus_default.ply");
  const auto a = runCli("mesh " + scene + " -o " + plain + " --resolution 24 --chord-tolerance 0");
  const auto b = runCli("mesh " + scene + " -o " + refined + " --resolution 24 --chord-tolerance 0.02");
  const auto d = runCli("mesh " + scene + " -o " + byDefault + " --resolution 24");
  REQUIRE(a.rc == 0);
  REQUIRE(b.rc == 0);
  REQUIRE(d.rc == 0);
  CHECK(a.out.find("chord refinement") == std::string::npos);
  // The default is 0.02: the same split edges and the same mesh as the explicit flag.
  const auto splitCount = [](const std::string& out) {  // N of "; N edges split by chord refinement"
    const std::size_t end = out.find(" edges split"), begin = out.rfind("; ", end);
    return end == std::string::npos || begin == std::string::npos ? std::string() : out.substr(begin + 2, end - begin - 2);
  };
  CHECK(!splitCount(d.out).empty());
  CHECK(splitCount(d.out) == splitCount(b.out));
  CHECK(hermite::loadMesh(byDefault).vertices == hermite::loadMesh(refined).vertices);
  CHECK(b.out.find("edges split by chord refinement") != std::string::npos);
  CHECK(b.out.find("closed manifold") != std::string::npos);
  const hermite::TriMesh m0 = hermite::loadMesh(plain), m1 = hermite::loadMesh(refined);
  const hermite::MeshCheck c = hermite::checkMesh(m1);
  CHECK(c.closedManifold());
  CHECK(c.eulerCharacteristic == 0);
  // Each split edge adds one vertex and two triangles (closed mesh).
  CHECK(m1.vertexCount() > m0.vertexCount());
  CHECK(m1.triangleCount() - m0.triangleCount() == 2 * (m1.vertexCount() - m0.vertexCount()));
  CHECK(runCli("mesh " + scene + " -o " + refined + " --chord-tolerance 2").rc == 2);
}

TEST_CASE("mesh without --resolution: 3D round(0.6·√N) cells within 64 – 256, 2D 64") {
  CHECK(hermite::app::autoMeshResolution(3, 0) == 64);
  CHECK(hermite::app::autoMeshResolution(3, 11000) == 64);
  CHECK(hermite::app::autoMeshResolution(3, 20000) == 85);
  CHECK(hermite::app::autoMeshResolution(3, 200000) == 256);
  CHECK(hermite::app::autoMeshResolution(3, 1000000) == 256);
  CHECK(hermite::app::autoMeshResolution(2, 1000000) == 64);
  // 20 000 points of a sphere as a data file: partition of unity, 85 cells per side, closed.
  std::ostringstream points;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {  // golden spiral: evenly spread, normals = positions
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
    points << r * std::cos(phi) << ' ' << r * std::sin(phi) << ' ' << z << ' ' << r * std::cos(phi) << ' '
           << r * std::sin(phi) << ' ' << z << '\n';
  }
  const std::string file = writeTemp("mesh_auto_sphere.xyzn", points.str());
  const auto r = runCli("mesh " + file + " -o " + tempPath("mesh_auto_sphere.ply"));
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("85x85x85 cells") != std::string::npos);
  CHECK(r.out.find("closed manifold") != std::string::npos);
}

TEST_CASE("mesh: an open scan fitted by partition of unity ends where its data ends, and the summary says so") {
  // 12 000 points of the upper half of a unit sphere (golden spiral), normals = positions: the
  // partition of unity (picked by size) has no data below the rim, so the mesh is open there.
  std::ostringstream points;
  const int n = 12000;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (i + 0.5) / n, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
    points << r * std::cos(phi) << ' ' << r * std::sin(phi) << ' ' << z << ' ' << r * std::cos(phi) << ' '
           << r * std::sin(phi) << ' ' << z << '\n';
  }
  const std::string file = writeTemp("mesh_open_cap.xyzn", points.str());
  const std::string out = tempPath("mesh_open_cap.ply");
  const auto r = runCli("mesh " + file + " -o " + out);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("open (the surface leaves view.bounds or ends where the field has no data)") != std::string::npos);
  CHECK_FALSE(hermite::checkMesh(hermite::loadMesh(out)).closedManifold());
}

TEST_CASE("mesh: a dense thin slab (flat faces at the data's extremes) closes as one watertight component") {
  // 60 000 points uniform by area on the faces of a 1 × 0.7 × 0.13 box, exact outward normals.
  // The partition of unity's boxes along the big flat faces are small, so their supports end
  // closer to the faces than a grid cell; the grid's corners beyond must still get a value
  // (PuNearField), or the cells across the faces are left out (half the slab was missing).
  const double size[3] = {1.0, 0.7, 0.13};
  const double area[3] = {size[1] * size[2], size[0] * size[2], size[0] * size[1]};  // faces ⟂ x, y, z
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::ostringstream points;
  points.precision(9);
  for (int i = 0; i < 60000; ++i) {
    double pick = u(rng) * (area[0] + area[1] + area[2]);
    int axis = 0;
    while (axis < 2 && pick > area[axis]) pick -= area[axis++];
    const double side = u(rng) < 0.5 ? 0.0 : 1.0;
    double p[3], n[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) p[k] = (k == axis ? side : u(rng)) * size[k];
    n[axis] = side > 0 ? 1.0 : -1.0;
    points << p[0] << ' ' << p[1] << ' ' << p[2] << ' ' << n[0] << ' ' << n[1] << ' ' << n[2] << '\n';
  }
  const std::string file = writeTemp("mesh_thin_slab.xyzn", points.str());
  const std::string out = tempPath("mesh_thin_slab.ply");
  const auto r = runCli("mesh " + file + " -o " + out);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("closed manifold") != std::string::npos);
  const hermite::MeshCheck c = hermite::checkMesh(hermite::loadMesh(out));
  CHECK(c.closedManifold());
  CHECK(c.components == 1);
  CHECK(c.eulerCharacteristic == 2);
}

TEST_CASE("mesh: a rod thinner than a grid cell between two balls stays joined (the grid is refined at its samples)") {
  // Two balls of radius 0.3 at x = ±0.5 joined by a rod of radius 0.012 along x at y = z = 0.018,
  // sampled with exact outward normals. At --resolution 64 over the default bounds the cells are
  // 0.037 wide and y = z = 0 is a grid line, so the rod's axis lies 0.025 from every grid line
  // along x and the uniform grid holds no point inside the rod: it meshes as two balls.
  constexpr double kAxis = 0.018, kRod = 0.012;
  const auto f = [&](const Eigen::Vector3d& q) {
    const Eigen::Vector3d axis(std::clamp(q.x(), -0.5, 0.5), kAxis, kAxis);
    return std::min({(q - Eigen::Vector3d(-0.5, 0, 0)).norm() - 0.3, (q - Eigen::Vector3d(0.5, 0, 0)).norm() - 0.3,
                     (q - axis).norm() - kRod});
  };
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::ostringstream points;
  points.precision(9);
  const auto add = [&](const Eigen::Vector3d& q, const Eigen::Vector3d& n) {
    if (f(q) > -1e-9) points << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
  };
  for (double cx : {-0.5, 0.5})
    for (int i = 0; i < 6000; ++i) {
      const Eigen::Vector3d v = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      add(Eigen::Vector3d(cx, 0, 0) + 0.3 * v, v);
    }
  for (int i = 0; i < 1500; ++i) {
    const double x = -0.25 + 0.5 * u(rng), t = 2 * M_PI * u(rng);
    const Eigen::Vector3d n(0, std::cos(t), std::sin(t));
    add(Eigen::Vector3d(x, kAxis, kAxis) + kRod * n, n);
  }
  const std::string file = writeTemp("mesh_thin_rod.xyzn", points.str());
  const std::string out = tempPath("mesh_thin_rod.ply");
  const auto r = runCli("mesh " + file + " -o " + out + " --resolution 64");
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("64x38x38 cells") != std::string::npos);
  CHECK(r.out.find("samples on parts thinner than a cell (0 still missed)") != std::string::npos);
  CHECK(r.out.find("closed manifold") != std::string::npos);
  const hermite::MeshCheck c = hermite::checkMesh(hermite::loadMesh(out), 1e-16);
  CHECK(c.closedManifold());
  CHECK(c.components == 1);
  CHECK(c.eulerCharacteristic == 2);
}

TEST_CASE("mesh: a ball sampled inside a solid one, against its samples' side, is left out and the summary says so") {
  // 6000 samples of a sphere of radius 0.5 and 300 of one of radius 0.06 at its centre, all with
  // outward normals: inside the big ball the small one's samples say "outside" beyond their own
  // surface, which no closed surface of the samples does. Its pieces lie where the samples'
  // winding number is about 1.5 and 1 (stray_pockets.h), not ½: left out.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::ostringstream points;
  points.precision(9);
  for (const auto& [radius, count] : {std::pair{0.5, 6000}, std::pair{0.06, 300}})
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d v = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const Eigen::Vector3d q = radius * v;
      points << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    }
  const std::string file = writeTemp("mesh_inner_ball.xyzn", points.str());
  const std::string out = tempPath("mesh_inner_ball.ply");
  const auto r = runCli("mesh " + file + " -o " + out);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("pieces off the samples' surface (by winding number) left out") != std::string::npos);
  CHECK(r.out.find("closed manifold") != std::string::npos);
  const hermite::TriMesh mesh = hermite::loadMesh(out);
  const hermite::MeshCheck c = hermite::checkMesh(mesh, 1e-16);
  CHECK(c.components == 1);
  CHECK(c.eulerCharacteristic == 2);
  const Eigen::ArrayXd radii = mesh.vertices.colwise().norm().transpose().array();
  CHECK(radii.minCoeff() > 0.48);  // nothing left of the small ball
  CHECK(radii.maxCoeff() < 0.52);
}
