#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/mesh_samples.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "core/base/errors.h"
#include "io/point_file.h"

using hermite::HermiteSamples;
using hermite::InputError;
using hermite::Vec;
namespace fs = std::filesystem;

namespace {

const std::string kPoints = std::string(HERMITE_FIXTURES) + "/points";

// Each test's own folder, named after this file's tests.
struct TempDir : hermite::testing::TempDir {
  TempDir() : hermite::testing::TempDir("hermite_io_test") {}
};

std::string load3dError(const std::string& path) {
  std::vector<std::string> warnings;
  try {
    hermite::loadPointFile3d(path, warnings);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

}  // namespace

TEST_CASE("io_points: dimension from the extension") {
  CHECK(hermite::pointFileDimension("a.xyz") == 3);
  CHECK(hermite::pointFileDimension("dir.v2/a.PWN") == 3);
  CHECK(hermite::pointFileDimension("a.xyzn") == 3);
  CHECK(hermite::pointFileDimension("a.xyn") == 2);
  CHECK_THROWS_WITH_AS(hermite::pointFileDimension("a.txt"),
                       "a.txt: unsupported point file extension '.txt' (supported: .xyz, .pwn, .xyzn with x y z "
                       "nx ny nz per line; .xyn with x y nx ny; .ply, .obj, .gltf, .glb, .off with vertex normals)",
                       InputError);
  CHECK_THROWS_AS(hermite::pointFileDimension("noextension"), InputError);
}

TEST_CASE("io_points: loads a 3D file and normalises its normals") {
  std::vector<std::string> warnings;
  const auto s = hermite::loadPointFile3d(kPoints + "/tetra.xyzn", warnings);
  CHECK(warnings.empty());
  REQUIRE(s.size() == 4);
  CHECK(s.points.col(1) == Eigen::Vector3d(1, -1, -1));
  CHECK(s.points.col(3) == Eigen::Vector3d(-1, -1, 1));
  CHECK(s.normals.col(0).isApprox(Eigen::Vector3d(1, 1, 1).normalized()));
  for (int i = 0; i < 4; ++i) CHECK(std::abs(s.normals.col(i).norm() - 1) < 1e-15);
}

TEST_CASE("io_points: CRLF line ends, comments, blank lines, signs and exponents") {
  std::vector<std::string> warnings;
  const auto fixture = hermite::loadPointFile3d(kPoints + "/crlf.xyzn", warnings);
  REQUIRE(fixture.size() == 2);
  CHECK(fixture.points.col(1) == Eigen::Vector3d(1, 2, 3));
  CHECK(fixture.normals.col(1) == Eigen::Vector3d(0, 0, -1));

  TempDir dir;
  const std::string path = dir.write("mixed.xyz",
                                     "\xEF\xBB\xBF# header\r\n"
                                     "\r\n"
                                     "  +1.5e0\t-2.25  3e-1 0 0 1\r\n"
                                     "\t# indented comment\r\n"
                                     ".5 -.5 1E2 +0 1 0   \r\n"
                                     "1e-400 0 0 1 0 0");  // no final newline; underflow reads as 0
  const auto s = hermite::loadPointFile3d(path, warnings);
  REQUIRE(s.size() == 3);
  CHECK(s.points.col(0) == Eigen::Vector3d(1.5, -2.25, 0.3));
  CHECK(s.points.col(1) == Eigen::Vector3d(0.5, -0.5, 100));
  CHECK(s.normals.col(1) == Eigen::Vector3d(0, 1, 0));
  CHECK(s.points.col(2) == Eigen::Vector3d(0, 0, 0));
}

TEST_CASE("io_points: 2D files") {
  std::vector<std::string> warnings;
  const auto s = hermite::loadPointFile2d(kPoints + "/circle.xyn", warnings);
  REQUIRE(s.size() == 4);
  CHECK(s.points.col(2) == Eigen::Vector2d(-1, 0));
  CHECK(s.normals.col(3) == Eigen::Vector2d(0, -1));

  TempDir dir;
  const std::string bad = dir.write("bad.xyn", "0 0 1 0\n1 1 1\n");
  CHECK_THROWS_WITH_AS(hermite::loadPointFile2d(bad, warnings),
                       (bad + ":2: expected 4 numbers (x y nx ny), got 3").c_str(), InputError);
  // Positions only: normals are estimated, with a warning saying so.
  std::string circle;
  for (int i = 0; i < 40; ++i)
    circle += std::to_string(std::cos(2 * M_PI * i / 40)) + " " + std::to_string(std::sin(2 * M_PI * i / 40)) + "\n";
  const std::string positions = dir.write("pos.xyn", circle);
  warnings.clear();
  const auto est = hermite::loadPointFile2d(positions, warnings);
  REQUIRE(est.size() == 40);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("has no normals (2 columns): normals estimated for all 40 samples") != std::string::npos);
  for (int i = 0; i < est.size(); ++i) CHECK(est.normals.col(i).dot(est.points.col(i).normalized()) > 0.99);
  // A file of the other dimension is refused by its extension.
  CHECK_THROWS_WITH_AS(hermite::loadPointFile2d(kPoints + "/tetra.xyzn", warnings),
                       (kPoints + "/tetra.xyzn: a 3D point file (.xyzn) cannot be used in a 2D scene; use .xyn (x y "
                                  "nx ny)")
                           .c_str(),
                       InputError);
  CHECK_THROWS_WITH_AS(hermite::loadPointFile3d(kPoints + "/circle.xyn", warnings),
                       (kPoints + "/circle.xyn: a 2D point file (.xyn) cannot be used in a 3D scene; use .xyz, .pwn "
                                  "or .xyzn (x y z nx ny nz)")
                           .c_str(),
                       InputError);
}

TEST_CASE("io_points: a .xyz file with 2 or 4 numbers per line is 2D data") {
  TempDir dir;
  std::string positions, oriented;
  for (int i = 0; i < 40; ++i) {
    const double c = std::cos(2 * M_PI * i / 40), s = std::sin(2 * M_PI * i / 40);
    positions += std::to_string(c) + " " + std::to_string(s) + "\n";
    oriented += std::to_string(2 * c) + "\t" + std::to_string(2 * s) + " " + std::to_string(c) + " " + std::to_string(s) + "\n";
  }
  const std::string two = dir.write("circle2.xyz", "# x y\n\n" + positions);
  const std::string four = dir.write("circle4.XYZ", oriented);
  CHECK(hermite::pointFileDimension(two) == 2);
  CHECK(hermite::pointFileDimension(four) == 2);
  CHECK(hermite::pointFileDimension(dir.write("three.xyz", "0 0 0\n1 0 0\n")) == 3);
  CHECK(hermite::pointFileDimension(dir.write("six.xyz", "0 0 0 0 0 1\n")) == 3);
  std::vector<std::string> warnings;
  const auto est = hermite::loadPointFile2d(two, warnings);
  REQUIRE(est.size() == 40);
  REQUIRE(warnings.size() == 1);  // normals estimated
  for (int i = 0; i < est.size(); ++i) CHECK(est.normals.col(i).dot(est.points.col(i).normalized()) > 0.99);
  warnings.clear();
  const auto given = hermite::loadPointFile2d(four, warnings);
  REQUIRE(given.size() == 40);
  CHECK(warnings.empty());
  CHECK(std::abs(given.points.col(10).norm() - 2) < 1e-5);
  CHECK(given.normals.col(10).dot(given.points.col(10).normalized()) > 1 - 1e-9);
  CHECK_THROWS_WITH_AS(hermite::loadPointFile3d(two, warnings),
                       (two + ": a 2D point file (.xyz with 2 or 4 numbers per line) cannot be used in a 3D scene; "
                              "use .xyz, .pwn or .xyzn (x y z nx ny nz)")
                           .c_str(),
                       InputError);
  // Every line must match the first one.
  const std::string mixed = dir.write("mixed2.xyz", "0 0\n1 0 0\n");
  CHECK_THROWS_WITH_AS(hermite::loadPointFile2d(mixed, warnings),
                       (mixed + ":2: expected 2 numbers (x y) like line 1, got 3").c_str(), InputError);
}

TEST_CASE("io_points: malformed files name the file and line") {
  const std::string p = kPoints;
  CHECK(load3dError(p + "/short_line.xyz") == p + "/short_line.xyz:4: expected 6 numbers (x y z nx ny nz), got 5");
  CHECK(load3dError(p + "/not_a_number.xyz") == p + "/not_a_number.xyz:2: 'abc' is not a number");
  CHECK(load3dError(p + "/nan.xyz") == p + "/nan.xyz:2: 'nan' is not a finite number");
  CHECK(load3dError(p + "/comments_only.xyz") == p + "/comments_only.xyz: no points");
  CHECK(load3dError(p + "/missing.xyz") == p + "/missing.xyz: cannot open (No such file or directory)");

  TempDir dir;
  const std::string four = dir.write("four.xyz", "0 0 0 0 0 1\r\n\r\n1 2 3 4\r\n");
  CHECK(load3dError(four) == four + ":3: expected 6 numbers (x y z nx ny nz), got 4");
  const std::string seven = dir.write("seven.xyz", "0 0 0 0 0 1 9\n");
  CHECK(load3dError(seven) == seven + ":1: expected 6 numbers (x y z nx ny nz), got 7");
  // Some lines with normals, some without: the first line decides, the first other line is reported.
  const std::string mixed = dir.write("mixed.xyz", "0 0 0\n1 0 0 1 0 0\n");
  CHECK(load3dError(mixed) == mixed + ":2: expected 3 numbers (x y z) like line 1, got 6");
  const std::string mixed2 = dir.write("mixed2.xyz", "1 0 0 1 0 0\n0 0 0\n");
  CHECK(load3dError(mixed2) == mixed2 + ":2: expected 6 numbers (x y z nx ny nz), got 3");
  const std::string glued = dir.write("glued.xyz", "0 0 0 0 0 1.5abc\n");
  CHECK(load3dError(glued) == glued + ":1: '1.5abc' is not a number");
  const std::string commas = dir.write("commas.xyz", "0,0,0,0,0,1\n");
  CHECK(load3dError(commas) == commas + ":1: '0,0,0,0,0,1' is not a number");
  const std::string infinite = dir.write("inf.xyz", "0 0 0 0 0 1\n# c\n0 0 -inf 0 0 1\n");
  CHECK(load3dError(infinite) == infinite + ":3: '-inf' is not a finite number");
  const std::string huge = dir.write("huge.xyz", "0 0 1e400 0 0 1\n");
  CHECK(load3dError(huge) == huge + ":1: '1e400' is not a finite number");
  const std::string empty = dir.write("empty.xyz", "");
  CHECK(load3dError(empty) == empty + ": no points");
  fs::create_directory(dir.path / "folder.xyz");
  CHECK(load3dError((dir.path / "folder.xyz").string()) ==
        (dir.path / "folder.xyz").string() + ": cannot open (it is a directory)");
}

TEST_CASE("io_points: duplicates are merged with a warning naming the file") {
  TempDir dir;
  const std::string path = dir.write("dups.xyz", "0 0 0 0 0 1\n1 0 0 1 0 0\n0 0 0 0 0 2\n");
  std::vector<std::string> warnings;
  const auto s = hermite::loadPointFile3d(path, warnings);
  CHECK(s.size() == 2);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].rfind(path + ": merged 1 exact duplicate sample", 0) == 0);
  const std::string conflict = dir.write("conflict.xyz", "0 0 0 0 0 1\n1 0 0 1 0 0\n0 0 0 0 1 0\n");
  CHECK(load3dError(conflict).rfind(conflict + ": samples 0 and 2 are at the same point", 0) == 0);
}

TEST_CASE("io_points: probe points") {
  const auto P = hermite::loadProbePoints3d(kPoints + "/probes.txt");
  REQUIRE(P.cols() == 2);
  CHECK(P.col(1) == Eigen::Vector3d(0.5, 0.25, -1));

  TempDir dir;
  const std::string p2 = dir.write("probes2.txt", "# x y\r\n1 2\r\n3 4\r\n5 6\r\n");
  const auto Q = hermite::loadProbePoints2d(p2);
  REQUIRE(Q.cols() == 3);
  CHECK(Q.col(2) == Eigen::Vector2d(5, 6));
  const std::string extra = dir.write("extra.txt", "0 0 0\n0 0 0 0 0 1\n");
  CHECK_THROWS_WITH_AS(hermite::loadProbePoints3d(extra), (extra + ":2: expected 3 numbers (x y z), got 6").c_str(),
                       InputError);
  CHECK_THROWS_WITH_AS(hermite::loadProbePoints2d(extra), (extra + ":1: expected 2 numbers (x y), got 3").c_str(),
                       InputError);
  const std::string none = dir.write("none.txt", "# nothing\n");
  CHECK_THROWS_WITH_AS(hermite::loadProbePoints3d(none), (none + ": no points").c_str(), InputError);
  const std::string word = dir.write("word.txt", "1 x 2\n");
  CHECK_THROWS_WITH_AS(hermite::loadProbePoints3d(word), (word + ":1: 'x' is not a number").c_str(), InputError);
  CHECK_THROWS_WITH_AS(hermite::loadProbePoints3d(dir.path.string() + "/absent.txt"),
                       (dir.path.string() + "/absent.txt: cannot open (No such file or directory)").c_str(),
                       InputError);
}

TEST_CASE("io_points: save and load round-trip every bit") {
  TempDir dir;
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  hermite::HermiteSamples<3> s;
  s.points.resize(3, 500);
  s.normals.resize(3, 500);
  for (int i = 0; i < 500; ++i) {
    s.points.col(i) = Eigen::Vector3d(g(rng), 1e-7 * g(rng), 1e9 * g(rng));
    s.normals.col(i) = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  }
  const std::string path = (dir.path / "out.xyzn").string();
  hermite::savePointFile(path, s);
  CHECK(dir.entries() == std::vector<std::string>{"out.xyzn"});
  // Random normals at random points describe no surface: the orientation check is off, the
  // file format alone is under test.
  const hermite::PointFileOptions asGiven{hermite::GivenNormals::Never};
  std::vector<std::string> warnings;
  const auto back = hermite::loadPointFile3d(path, warnings, asGiven);
  CHECK(warnings.empty());
  CHECK(back.points == s.points);
  // Re-normalising a unit normal may move it by an ulp, not more.
  CHECK((back.normals - s.normals).cwiseAbs().maxCoeff() <= 4e-16);

  hermite::HermiteSamples<2> s2;
  s2.points.resize(2, 3);
  s2.normals.resize(2, 3);
  s2.points << 0.1, 0.2, 0.3,  // x of the three samples
               -1e-300, 5, 6;  // y
  s2.normals << 1, 0, -1,
                0, 1, 0;
  const std::string path2 = (dir.path / "out.xyn").string();
  hermite::savePointFile(path2, s2);
  const auto back2 = hermite::loadPointFile2d(path2, warnings);
  CHECK(back2.points == s2.points);
  CHECK(back2.normals == s2.normals);

  // A failed save leaves the old file in place.
  CHECK_THROWS_AS(hermite::savePointFile((dir.path / "missing_dir" / "x.xyzn").string(), s), hermite::EnvironmentError);
  CHECK(dir.entries() == std::vector<std::string>{"out.xyn", "out.xyzn"});
}

TEST_CASE("io_points: large files load quickly") {
  TempDir dir;
  const std::string path = (dir.path / "big.xyz").string();
  {
    std::mt19937 rng(5);
    std::normal_distribution<double> g(0, 1);
    hermite::HermiteSamples<3> s;
    const int n = 200000;
    s.points.resize(3, n);
    s.normals.resize(3, n);
    for (int i = 0; i < n; ++i) {
      s.points.col(i) = Eigen::Vector3d(g(rng), g(rng), g(rng));
      s.normals.col(i) = s.points.col(i).normalized();
    }
    hermite::savePointFile(path, s);
  }
  std::vector<std::string> warnings;
  const auto start = std::chrono::steady_clock::now();
  const auto s = hermite::loadPointFile3d(path, warnings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(s.size() == 200000);
  CHECK(seconds < 5.0);  // a generous bound that a parser built on streams instead of from_chars would approach
}

TEST_CASE("io_points: zero normals, all or some, are estimated and oriented with a warning") {
  TempDir dir;
  const HermiteSamples<3> sphere = hermite::testing::goldenSphere(800, 1.0);
  // Six columns, every normal zero (CGAL's blobby.xyz): estimated, outward, one warning.
  std::string allZero, someZero;
  int zeroed = 0;
  for (int i = 0; i < sphere.size(); ++i) {
    const Vec<3> p = sphere.points.col(i);
    char line[200];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g 0 0 0\n", p.x(), p.y(), p.z());
    allZero += line;
    // Every seventh normal zero, the others given pointing inward: the estimated ones follow them.
    const Vec<3> n = i % 7 == 0 ? Vec<3>::Zero() : Vec<3>(-sphere.normals.col(i));
    zeroed += i % 7 == 0;
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(), n.x(), n.y(), n.z());
    someZero += line;
  }
  std::vector<std::string> warnings;
  const auto all = hermite::loadPointFile3d(dir.write("blobby.xyz", allZero), warnings);
  REQUIRE(all.size() == sphere.size());
  for (int i = 0; i < all.size(); ++i) CHECK(all.normals.col(i).dot(sphere.normals.col(i)) > 0.99);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("800 of 800 normals are zero: normals estimated for all 800 samples") != std::string::npos);

  warnings.clear();
  const auto some = hermite::loadPointFile3d(dir.write("some.xyz", someZero), warnings);
  REQUIRE(some.size() == sphere.size());
  for (int i = 0; i < some.size(); ++i) CHECK(some.normals.col(i).dot(sphere.normals.col(i)) < -0.99);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find(std::to_string(zeroed) + " of 800 normals are zero: normals estimated for those " +
                         std::to_string(zeroed)) != std::string::npos);
  CHECK(warnings[0].find("consistently with the given normals") != std::string::npos);

  // The fixture's second normal is zero: estimated from the first.
  warnings.clear();
  const auto two = hermite::loadPointFile3d(kPoints + "/zero_normal.xyz", warnings);
  REQUIRE(two.size() == 2);
  CHECK(two.normals.col(1).norm() == doctest::Approx(1.0));
  CHECK(warnings.size() == 1);
}

// CGAL's hippo2.ply: a PLY point set whose normals are partly zero. Zero normals in mesh-format
// files are estimated as in text files; on a mesh they come from the faces first.
TEST_CASE("io_points: zero normals in PLY point sets and OBJ meshes are completed with a warning") {
  TempDir dir;
  const HermiteSamples<3> sphere = hermite::testing::goldenSphere(600, 1.0);
  std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(sphere.size()) +
                    "\nproperty double x\nproperty double y\nproperty double z\n"
                    "property double nx\nproperty double ny\nproperty double nz\nend_header\n";
  int zeroed = 0;
  for (int i = 0; i < sphere.size(); ++i) {
    const Vec<3> p = sphere.points.col(i);
    const Vec<3> n = i % 5 == 0 ? Vec<3>::Zero() : Vec<3>(sphere.normals.col(i));
    zeroed += i % 5 == 0;
    char line[200];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(), n.x(), n.y(), n.z());
    ply += line;
  }
  std::vector<std::string> warnings;
  const auto points = hermite::loadPointFile3d(dir.write("hippo.ply", ply), warnings);
  REQUIRE(points.size() == sphere.size());
  for (int i = 0; i < points.size(); ++i) CHECK(points.normals.col(i).dot(sphere.normals.col(i)) > 0.99);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find(std::to_string(zeroed) + " of 600 normals are zero: normals estimated for those") !=
        std::string::npos);

  // A tetrahedron-like OBJ (counter-clockwise from outside) whose vertex 0 has a zero normal: it
  // takes the area-weighted face normal, the given ones stay as they are.
  const std::string obj =
      "v 1 1 1\nv -1 -1 1\nv -1 1 -1\nv 1 -1 -1\n"
      "vn 0 0 0\nvn -1 -1 1\nvn -1 1 -1\nvn 1 -1 -1\n"
      "f 1//1 2//2 4//4\nf 1//1 4//4 3//3\nf 1//1 3//3 2//2\nf 2//2 3//3 4//4\n";
  warnings.clear();
  const auto tet = hermite::loadPointFile3d(dir.write("tet.obj", obj), warnings);
  REQUIRE(tet.size() == 4);
  CHECK(tet.normals.col(0).dot(Vec<3>(1, 1, 1).normalized()) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(tet.normals.col(1).dot(Vec<3>(-1, -1, 1).normalized()) == doctest::Approx(1.0).epsilon(1e-12));
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("1 of 4 vertex normals are zero: 1 taken from the area-weighted face normals") !=
        std::string::npos);
}

// CGAL's cube.pwn gives normal lines with arbitrary signs, half its faces inward: the loader
// re-orients them (lines kept) with a warning; data.orient_normals false keeps them as given.
TEST_CASE("io_points: unoriented given normals are re-oriented with a warning, unless switched off") {
  TempDir dir;
  const HermiteSamples<3> box = hermite::testing::sampleMesh(
      hermite::testing::boxMesh(Vec<3>(-0.5, -0.37, -0.37), Vec<3>(0.5, 0.37, 0.37)), 20000, 3);
  std::mt19937 rng(8);
  hermite::Points<3> given = box.normals;
  std::string text;
  for (int i = 0; i < box.size(); ++i) {
    if (rng() & 1) given.col(i) *= -1;
    const Vec<3> p = box.points.col(i), n = given.col(i);
    char line[200];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(), n.x(), n.y(), n.z());
    text += line;
  }
  const std::string path = dir.write("cube.pwn", text);
  std::vector<std::string> warnings;
  const auto fixed = hermite::loadPointFile3d(path, warnings);
  REQUIRE(fixed.size() == box.size());
  CHECK(hermite::testing::flippedFraction(fixed.normals, box.normals) <= 0.005);
  int turned = 0;
  for (int i = 0; i < box.size(); ++i) {
    CHECK(std::abs(fixed.normals.col(i).dot(given.col(i))) == doctest::Approx(1.0).epsilon(1e-12));  // same line
    turned += fixed.normals.col(i).dot(given.col(i)) < 0;
  }
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].rfind(path + ": normals are not consistently oriented (", 0) == 0);
  CHECK(warnings[0].find("re-oriented " + std::to_string(turned) + " of 20000 normals (their lines kept)") !=
        std::string::npos);
  CHECK(warnings[0].find("set data.orient_normals to false") != std::string::npos);

  warnings.clear();
  const auto kept = hermite::loadPointFile3d(path, warnings, {hermite::GivenNormals::Never});
  CHECK(warnings.empty());
  CHECK((kept.normals - given).cwiseAbs().maxCoeff() <= 4e-16);

  // Consistent normals, inward ones too, pass unchanged and without a warning.
  std::string inward;
  for (int i = 0; i < box.size(); ++i) {
    const Vec<3> p = box.points.col(i), n = -box.normals.col(i);
    char line[200];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(), n.x(), n.y(), n.z());
    inward += line;
  }
  warnings.clear();
  const auto in = hermite::loadPointFile3d(dir.write("inward.pwn", inward), warnings);
  CHECK(warnings.empty());
  CHECK((in.normals + box.normals).cwiseAbs().maxCoeff() <= 4e-16);
}

namespace {

// A cube [−1, 1]³ as an OBJ split at its edges, as exporters write flat-shaded meshes: each face
// has its own 4 vertices (24 in all, 3 at each corner), two triangles counter-clockwise from
// outside, and with `flatNormals` each face's own normal on its vertices. With `shared`, the 8
// corners once each instead (no normals).
std::string cubeObj(bool flatNormals, bool shared = false) {
  std::string obj;
  int next = 1;
  std::vector<int> cornerId(8, 0);
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      int ids[4];
      const int uw[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (int k = 0; k < 4; ++k) {
        const int j = side > 0 ? k : 3 - k;  // counter-clockwise about the outward normal
        int c[3];
        c[axis] = side;
        c[u] = uw[j][0];
        c[w] = uw[j][1];
        const int corner = (c[0] > 0) | ((c[1] > 0) << 1) | ((c[2] > 0) << 2);
        if (shared && cornerId[static_cast<size_t>(corner)] > 0) {
          ids[k] = cornerId[static_cast<size_t>(corner)];
          continue;
        }
        obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
        if (flatNormals)
          obj += "vn " + std::to_string(axis == 0 ? side : 0) + " " + std::to_string(axis == 1 ? side : 0) + " " +
                 std::to_string(axis == 2 ? side : 0) + "\n";
        ids[k] = next++;
        if (shared) cornerId[static_cast<size_t>(corner)] = ids[k];
      }
      const auto ref = [&](int i) { return flatNormals ? std::to_string(i) + "//" + std::to_string(i) : std::to_string(i); };
      obj += "f " + ref(ids[0]) + " " + ref(ids[1]) + " " + ref(ids[2]) + "\n";
      obj += "f " + ref(ids[0]) + " " + ref(ids[2]) + " " + ref(ids[3]) + "\n";
    }
  return obj;
}

// The sample at position p (exactly), or −1.
int sampleAt(const HermiteSamples<3>& s, const Vec<3>& p) {
  for (int i = 0; i < s.size(); ++i)
    if (s.points.col(i) == p) return i;
  return -1;
}

}  // namespace

TEST_CASE("io_points: a mesh split at its edges is one sample per position, normals from all the faces about it") {
  TempDir dir;
  std::vector<std::string> warnings;
  // No normals: the welded mesh's area-weighted normals, the same as the unsplit cube's.
  const auto split = hermite::loadPointFile3d(dir.write("split.obj", cubeObj(false)), warnings);
  std::vector<std::string> sharedWarnings;
  const auto shared = hermite::loadPointFile3d(dir.write("shared.obj", cubeObj(false, true)), sharedWarnings);
  REQUIRE(shared.size() == 8);
  REQUIRE(split.size() == 8);
  for (int i = 0; i < 8; ++i) {
    const int j = sampleAt(split, shared.points.col(i));
    REQUIRE(j >= 0);
    CHECK((split.normals.col(j) - shared.normals.col(i)).norm() <= 1e-15);
    CHECK(split.normals.col(j).dot(shared.points.col(i).normalized()) > 0.9);  // outward, about the diagonal
  }
  CHECK(std::any_of(warnings.begin(), warnings.end(),
                    [](const std::string& w) { return w.find("merged 16 exact duplicate samples") != std::string::npos; }));

  // Flat normals: each corner's three face normals give their mean, the cube's diagonal.
  warnings.clear();
  const auto flat = hermite::loadPointFile3d(dir.write("flat.obj", cubeObj(true)), warnings);
  REQUIRE(flat.size() == 8);
  for (int i = 0; i < 8; ++i)
    CHECK(flat.normals.col(i).dot(flat.points.col(i).normalized()) == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("flat.obj: 16 vertices repeat the position of another with a different normal") != std::string::npos;
  }));
}

TEST_CASE("io_points: a cloud as thick as its spacing is warned about as noisy; a sampled surface is not") {
  TempDir dir;
  const hermite::HermiteSamples<3> sphere = hermite::testing::goldenSphere(5000);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.08);  // twice the spacing of 5 000 points on a unit sphere
  std::string clean, rough;
  for (int i = 0; i < sphere.size(); ++i) {
    const Eigen::Vector3d p = sphere.points.col(i), q = p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    clean += std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
    rough += std::to_string(q.x()) + " " + std::to_string(q.y()) + " " + std::to_string(q.z()) + "\n";
  }
  const auto noisyWarning = [](const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings)
      if (w.find("the samples look noisy") != std::string::npos) return w;
    return std::string();
  };
  std::vector<std::string> warnings;
  hermite::loadPointFile3d(dir.write("clean.xyz", clean), warnings);
  CHECK(noisyWarning(warnings).empty());
  warnings.clear();
  const std::string path = dir.write("rough.xyz", rough);
  const hermite::HermiteSamples<3> s = hermite::loadPointFile3d(path, warnings);
  const std::string w = noisyWarning(warnings);
  CHECK(w.rfind(path + ": the samples look noisy: they lie in a layer 0.", 0) == 0);
  CHECK(w.find("fit.smoothing") != std::string::npos);
  // Its normals are estimated as one sheet over 40 neighbours: outward, as the sphere's (with the
  // defaults, the gap rule turned about half of them inward).
  CHECK(warnings[0].find("by PCA over 40 nearest neighbours (the cloud is noisy") != std::string::npos);
  int outward = 0;
  for (int i = 0; i < s.size(); ++i) outward += s.points.col(i).dot(s.normals.col(i)) > 0;
  CHECK(outward >= 0.98 * s.size());
}
