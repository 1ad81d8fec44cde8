// Normal-orientation yardstick (issue 17 item 3, docs/performance.md "Normal orientation"):
// samples N points uniformly by area from a closed, outward-oriented triangle mesh (each with
// its triangle's unit normal: the truth), then either estimates the normals from the positions
// alone (estimateNormals) or, with --unoriented, gives the true normal lines with random signs
// and re-orients them (orientNormalLines); prints the fraction pointing against the truth.
//
//   normal_flips MESH.off|slab|curl|shell N [--seed S] [--unoriented] [--gap G] [--flipped OUT.xyz]
//   normal_flips --sphere CLOUD.xyz   (x y z per line, a noisy sphere such as CGAL's sphere_20k.xyz:
//                                      the truth is the direction from the centroid)
//
// slab, curl and shell are thin shapes whose two sheets lie G mean sample spacings apart
// (G = 2.5 by default: inside one another's 10-neighbourhood): a 1 × 1 slab, the same slab
// curled through 270° about an axis (radius 1/(1.5π)), and a hollow ball (radii 1 and 1 − gap).
// Output, one line: name N seconds flipped fraction (flipped / N), then "lines>30° F (C)": the
// fraction whose unsigned line is more than 30° off the truth (|n̂·n| < cos 30°, a wrong plane
// rather than a wrong sign), and "flipped-on-good-lines C": the flipped ones among the others
// (pure sign errors). --flipped writes the flipped points with their true normals
// (x y z nx ny nz) for a look; with NORMAL_FLIPS_DUMP=FILE in the environment every sample is
// written there as x y z, true normal, estimated normal (9 numbers a line).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/mesh/tri_mesh.h"
#include "core/points/normal_estimation.h"
#include "io/mesh_file.h"
#include "support/mesh_samples.h"
#include "support/thin_shapes.h"

using namespace hermite;

namespace {

TriMesh shapeByName(const std::string& name, int n, double gap) {
  if (name == "slab") return testing::boxMesh(Vec<3>(0, 0, 0), Vec<3>(1, 1, gap * std::sqrt(2.0 / n)));
  if (name == "curl") return testing::curledPlate(gap * std::sqrt(2.0 / n));
  if (name == "shell") return testing::hollowBall(gap * std::sqrt(8 * M_PI / n));
  return loadMeshFile(name);
}

// The samples whose estimate points against the truth, as x y z nx ny nz (true normals).
void writeFlipped(const std::string& path, const HermiteSamples<3>& s, const Points<3>& estimated) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw InputError(path + ": cannot open for writing");
  for (int i = 0; i < s.size(); ++i)
    if (estimated.col(i).dot(s.normals.col(i)) < 0)
      std::fprintf(f, "%.9g %.9g %.9g %.9g %.9g %.9g\n", s.points(0, i), s.points(1, i), s.points(2, i),
                   s.normals(0, i), s.normals(1, i), s.normals(2, i));
  std::fclose(f);
}

}  // namespace

// `normal_flips --check FILE` (x y z nx ny nz per line): prints orientationDisagreement and how
// many signs orientNormalLines changes; `normal_flips --check FILE OUT.xyz` also writes the
// re-oriented samples.
int checkFile(const char* path, const char* out) {
  std::FILE* f = std::fopen(path, "r");
  if (!f) return std::fprintf(stderr, "normal_flips: cannot open %s\n", path), 1;
  std::vector<double> v;
  double x[6];
  while (std::fscanf(f, "%lf %lf %lf %lf %lf %lf", x, x + 1, x + 2, x + 3, x + 4, x + 5) == 6) v.insert(v.end(), x, x + 6);
  std::fclose(f);
  const Eigen::Index n = static_cast<Eigen::Index>(v.size() / 6);
  const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> m(v.data(), 6, n);
  const Points<3> P = m.topRows(3), N = m.bottomRows(3);
  Points<3> oriented = N;
  const int changed = orientNormalLines<3>(P, oriented);
  if (out) writeFlipped(out, HermiteSamples<3>{P, oriented}, -oriented);  // every sample, re-oriented
  std::printf("%s %ld disagreement %.5f re-orienting changes %d (%.5f)\n", path, long(n),
              orientationDisagreement<3>(P, N), changed, double(changed) / double(n));
  return 0;
}

// `normal_flips --sphere FILE` (x y z per line, sampled round a sphere): estimates the normals
// and compares them with the directions from the centroid.
int sphereFile(const char* path) {
  std::FILE* f = std::fopen(path, "r");
  if (!f) return std::fprintf(stderr, "normal_flips: cannot open %s\n", path), 1;
  std::vector<double> v;
  double x[3];
  while (std::fscanf(f, "%lf %lf %lf%*[^\n]", x, x + 1, x + 2) == 3) v.insert(v.end(), x, x + 3);
  std::fclose(f);
  const Eigen::Index n = static_cast<Eigen::Index>(v.size() / 3);
  const Points<3> P = Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(v.data(), 3, n);
  const Vec<3> centre = P.rowwise().mean();
  const Points<3> truth = (P.colwise() - centre).colwise().normalized();
  const auto t0 = std::chrono::steady_clock::now();
  const Points<3> estimated = estimateNormals<3>(P);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double flipped = testing::flippedFraction(estimated, truth);
  std::printf("%s %ld %.2f %.5f (%ld)\n", path, long(n), seconds, flipped, std::lround(flipped * double(n)));
  return 0;
}

int main(int argc, char** argv) {
  if (argc >= 3 && std::string(argv[1]) == "--sphere") return sphereFile(argv[2]);
  if (argc >= 3 && std::string(argv[1]) == "--check") return checkFile(argv[2], argc > 3 ? argv[3] : nullptr);
  if (argc < 3) {
    std::fprintf(stderr, "usage: normal_flips MESH.off|slab|curl|shell N [--seed S] [--unoriented] [--gap G]\n");
    return 2;
  }
  const std::string name = argv[1];
  const int n = std::atoi(argv[2]);
  unsigned seed = 1;
  bool unoriented = false;
  double gap = 2.5;
  std::string flippedPath;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--seed" && a + 1 < argc) seed = static_cast<unsigned>(std::atoi(argv[++a]));
    else if (arg == "--unoriented") unoriented = true;
    else if (arg == "--gap" && a + 1 < argc) gap = std::atof(argv[++a]);
    else if (arg == "--flipped" && a + 1 < argc) flippedPath = argv[++a];
    else return std::fprintf(stderr, "normal_flips: unknown argument %s\n", arg.c_str()), 2;
  }
  try {
    const HermiteSamples<3> s = testing::sampleMesh(shapeByName(name, n, gap), n, seed);
    Points<3> estimated = s.normals;
    const auto t0 = std::chrono::steady_clock::now();
    if (unoriented) {
      std::mt19937 rng(seed + 1);
      for (int i = 0; i < n; ++i)
        if (rng() & 1) estimated.col(i) = -estimated.col(i);
      orientNormalLines<3>(s.points, estimated);
    } else {
      estimated = estimateNormals<3>(s.points);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double flipped = testing::flippedFraction(estimated, s.normals);
    if (!flippedPath.empty()) writeFlipped(flippedPath, s, estimated);
    if (const char* dump = std::getenv("NORMAL_FLIPS_DUMP")) {
      std::FILE* f = std::fopen(dump, "w");
      for (int i = 0; f && i < n; ++i)
        std::fprintf(f, "%.9g %.9g %.9g %.6f %.6f %.6f %.6f %.6f %.6f\n", s.points(0, i), s.points(1, i), s.points(2, i),
                     s.normals(0, i), s.normals(1, i), s.normals(2, i), estimated(0, i), estimated(1, i), estimated(2, i));
      if (f) std::fclose(f);
    }
    int badLines = 0, signOnly = 0;
    for (int i = 0; i < n; ++i) {
      const double c = estimated.col(i).normalized().dot(s.normals.col(i));
      if (std::abs(c) < std::cos(M_PI / 6)) ++badLines;
      else signOnly += c < 0;
    }
    std::printf("%s %d %.2f %.5f (%d) lines>30° %.5f (%d) flipped-on-good-lines %d\n", name.c_str(), n, seconds,
                flipped, int(std::lround(flipped * n)), double(badLines) / n, badLines, signOnly);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "normal_flips: %s\n", e.what());
    return 1;
  }
  return 0;
}
