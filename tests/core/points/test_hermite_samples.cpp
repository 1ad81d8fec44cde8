#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/points/hermite_samples.h"

using hermite::HermiteSamples;
using hermite::InputError;
using hermite::Points;

namespace {

template <int Dim>
HermiteSamples<Dim> makeSamples(const std::vector<std::vector<double>>& rows) {
  HermiteSamples<Dim> s;
  s.points.resize(Dim, static_cast<Eigen::Index>(rows.size()));
  s.normals.resize(Dim, static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int k = 0; k < Dim; ++k) {
      s.points(k, static_cast<Eigen::Index>(i)) = rows[i][static_cast<std::size_t>(k)];
      s.normals(k, static_cast<Eigen::Index>(i)) = rows[i][static_cast<std::size_t>(Dim + k)];
    }
  return s;
}

template <int Dim>
std::string validationError(HermiteSamples<Dim> s) {
  std::vector<std::string> warnings;
  try {
    hermite::validateSamples(s, warnings, "src");
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

template <int Dim>
double bruteForceSpacing(const Points<Dim>& P) {
  double sum = 0;
  for (Eigen::Index i = 0; i < P.cols(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < P.cols(); ++j)
      if (j != i) best = std::min(best, (P.col(i) - P.col(j)).norm());
    sum += best;
  }
  return sum / double(P.cols());
}

}  // namespace

TEST_CASE("samples: normals are normalised") {
  auto s = makeSamples<3>({{0, 0, 0, 0, 0, 2}, {1, 0, 0, 3, 4, 0}, {0, 1, 0, 1e-200, 0, 0}, {0, 0, 1, 1e200, 1e200, 0}});
  std::vector<std::string> warnings;
  hermite::validateSamples(s, warnings, "src");
  CHECK(warnings.empty());
  REQUIRE(s.size() == 4);
  CHECK(s.normals.col(0).isApprox(Eigen::Vector3d(0, 0, 1)));
  CHECK(s.normals.col(1).isApprox(Eigen::Vector3d(0.6, 0.8, 0)));
  CHECK(s.normals.col(2) == Eigen::Vector3d(1, 0, 0));  // tiny normals do not underflow
  CHECK(s.normals.col(3).isApprox(Eigen::Vector3d(std::sqrt(0.5), std::sqrt(0.5), 0)));  // nor huge overflow
  for (int i = 0; i < 4; ++i) CHECK(std::abs(s.normals.col(i).norm() - 1.0) < 1e-15);

  auto s2 = makeSamples<2>({{0, 0, -5, 0}});
  hermite::validateSamples(s2, warnings, "src");
  CHECK(s2.normals.col(0) == Eigen::Vector2d(-1, 0));
}

TEST_CASE("samples: invalid samples name the source and the 0-based index") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(validationError(makeSamples<3>({{0, 0, 0, 0, 0, 1}, {1, 1, 1, 0, 0, 0}})) == "src: sample 1: normal is zero");
  CHECK(validationError(makeSamples<3>({{0, 0, 0, 0, 0, 1}, {1, 1, 1, 0, 0, 1}, {1, 2, 3, 0, 0, 1},
                                        {0, nan, 0, 0, 0, 1}})) == "src: sample 3: non-finite coordinate (0, nan, 0)");
  CHECK(validationError(makeSamples<2>({{0, 0, inf, 1}})) == "src: sample 0: non-finite normal (inf, 1)");
  CHECK(validationError(makeSamples<2>({{0, -inf, 0, 1}})) == "src: sample 0: non-finite coordinate (0, -inf)");
  CHECK(validationError(makeSamples<2>({{0, 0, 0, 0}})) == "src: sample 0: normal is zero");
  HermiteSamples<3> mismatched;
  mismatched.points.resize(3, 4);
  mismatched.normals.resize(3, 3);
  mismatched.points.setZero();
  mismatched.normals.setOnes();
  CHECK(validationError(mismatched) == "src: 4 points but 3 normals (one normal per point)");
}

TEST_CASE("samples: exact duplicates with the same normal are merged with a warning") {
  // Samples 2 and 4 repeat sample 0; sample 5 repeats 3 with a normal that only differs in length;
  // -0.0 and 0.0 are the same coordinate.
  auto s = makeSamples<3>({{0, 0, 0, 0, 0, 1},
                           {1, 0, 0, 1, 0, 0},
                           {0, 0, 0, 0, 0, 3},
                           {0, 1, 0, 0, 1, 0},
                           {-0.0, 0, 0, 0, 0, 1},
                           {0, 1, 0, 0, 7, 0},
                           {0, 0, 1e-300, 0, 0, 1}});
  std::vector<std::string> warnings;
  hermite::validateSamples(s, warnings, "data.xyz");
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].rfind("data.xyz: merged 3 exact duplicate samples", 0) == 0);
  REQUIRE(s.size() == 4);
  // The first of each group survives and the order is kept.
  CHECK(s.points.col(0) == Eigen::Vector3d(0, 0, 0));
  CHECK(s.points.col(1) == Eigen::Vector3d(1, 0, 0));
  CHECK(s.points.col(2) == Eigen::Vector3d(0, 1, 0));
  CHECK(s.points.col(3) == Eigen::Vector3d(0, 0, 1e-300));  // near but not exact: kept
  CHECK(s.normals.col(2) == Eigen::Vector3d(0, 1, 0));

  auto two = makeSamples<2>({{0.5, 0.5, 0, 1}, {0.5, 0.5, 0, 1}, {0.25, 0.5, 0, 1}});
  warnings.clear();
  hermite::validateSamples(two, warnings, "inline data");
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].rfind("inline data: merged 1 exact duplicate sample", 0) == 0);
  CHECK(two.size() == 2);
}

TEST_CASE("samples: duplicates with conflicting normals are rejected naming both samples") {
  const std::string message = validationError(
      makeSamples<3>({{0, 0, 0, 0, 0, 1}, {5, 5, 5, 1, 0, 0}, {2, 0, 0, 1, 0, 0}, {5, 5, 5, 0, 1, 0}}));
  CHECK(message == "src: samples 1 and 3 are at the same point (5, 5, 5) but have different normals (1, 0, 0) "
                   "and (0, 1, 0)");
  // Normals that differ by more than 1e-12 after normalisation conflict.
  // Flat constant tables: GCC 12.2 with AVX-512 (-march=native on this project's machines) and
  // -O2/-O3 miscompiles the stack initialisation of `{{1, 1, 1, 0}, {1, 1, 1, 1e-6}}`
  // (rows[0][3] reads 1); the SLP vectorizer is at fault (-fno-tree-slp-vectorize fixes it).
  static constexpr double kFar[] = {1, 1, 1, 0, 1, 1, 1, 1e-6};
  static constexpr double kNear[] = {1, 1, 1, 0, 1, 1, 1, 1e-14};
  auto fromTable = [](const double* table) {
    HermiteSamples<2> s;
    s.points = Eigen::Map<const Eigen::Matrix<double, 4, 2>>(table).topRows<2>();
    s.normals = Eigen::Map<const Eigen::Matrix<double, 4, 2>>(table).bottomRows<2>();
    return s;
  };
  CHECK(validationError(fromTable(kFar)).find("samples 0 and 1") != std::string::npos);
  CHECK(validationError(fromTable(kNear)) == "<no error>");
}

TEST_CASE("samples: duplicate detection scales to many samples") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 200000;
  HermiteSamples<3> s;
  s.points.resize(3, n);
  s.normals.resize(3, n);
  for (int i = 0; i < n; ++i) {
    s.points.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    s.normals.col(i) = Eigen::Vector3d(0, 0, 1);
  }
  for (int i = 0; i < 1000; ++i) s.points.col(n - 1 - i) = s.points.col(i);
  std::vector<std::string> warnings;
  const auto start = std::chrono::steady_clock::now();
  hermite::validateSamples(s, warnings, "big");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(s.size() == n - 1000);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].rfind("big: merged 1000 exact duplicate samples", 0) == 0);
  CHECK(seconds < 5.0);  // O(N log N): well under a second; O(N²) would take minutes
}

TEST_CASE("samples: meanSampleSpacing on regular grids equals the spacing") {
  SUBCASE("2D") {
    const double h = 0.1;
    Points<2> P(2, 17 * 13);
    for (int i = 0; i < 17; ++i)
      for (int j = 0; j < 13; ++j) P.col(i * 13 + j) = Eigen::Vector2d(0.3 + i * h, -1.0 + j * h);
    CHECK(std::abs(hermite::meanSampleSpacing<2>(P) - h) < 1e-12);
  }
  SUBCASE("3D") {
    const double h = 0.25;
    Points<3> P(3, 8 * 9 * 10);
    int c = 0;
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 9; ++j)
        for (int k = 0; k < 10; ++k) P.col(c++) = Eigen::Vector3d(i * h, 5 + j * h, -3 + k * h);
    CHECK(std::abs(hermite::meanSampleSpacing<3>(P) - h) < 1e-12);
  }
  SUBCASE("3D grid on a plane (a degenerate bounding box)") {
    const double h = 0.01;
    Points<3> P(3, 50 * 40);
    for (int i = 0; i < 50; ++i)
      for (int j = 0; j < 40; ++j) P.col(i * 40 + j) = Eigen::Vector3d(i * h, 2.0, j * h);
    CHECK(std::abs(hermite::meanSampleSpacing<3>(P) - h) < 1e-12);
  }
  SUBCASE("points on a line") {
    Points<2> P(2, 11);
    for (int i = 0; i < 11; ++i) P.col(i) = Eigen::Vector2d(i * 0.5, 0);
    CHECK(std::abs(hermite::meanSampleSpacing<2>(P) - 0.5) < 1e-12);
  }
}

TEST_CASE("samples: meanSampleSpacing matches brute force on irregular data") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  SUBCASE("uniform in a box (3D)") {
    Points<3> P(3, 2000);
    for (int i = 0; i < P.cols(); ++i) P.col(i) = Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
    CHECK(hermite::meanSampleSpacing<3>(P) == doctest::Approx(bruteForceSpacing<3>(P)).epsilon(1e-14));
  }
  SUBCASE("on a sphere (samples on a surface)") {
    Points<3> P(3, 3000);
    for (int i = 0; i < P.cols(); ++i) P.col(i) = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    CHECK(hermite::meanSampleSpacing<3>(P) == doctest::Approx(bruteForceSpacing<3>(P)).epsilon(1e-14));
  }
  SUBCASE("on a circle (2D curve)") {
    Points<2> P(2, 2500);
    for (int i = 0; i < P.cols(); ++i) P.col(i) = Eigen::Vector2d(g(rng), g(rng)).normalized();
    CHECK(hermite::meanSampleSpacing<2>(P) == doctest::Approx(bruteForceSpacing<2>(P)).epsilon(1e-14));
  }
  SUBCASE("a dense cluster and far outliers") {
    Points<3> P(3, 1500);
    for (int i = 0; i < P.cols(); ++i) P.col(i) = 1e-4 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    P.col(0) = Eigen::Vector3d(100, 0, 0);
    P.col(1) = Eigen::Vector3d(-50, 30, 7);
    P.col(2) = Eigen::Vector3d(-50, 30, 7.5);
    CHECK(hermite::meanSampleSpacing<3>(P) == doctest::Approx(bruteForceSpacing<3>(P)).epsilon(1e-14));
  }
  SUBCASE("duplicates give 0 for their samples") {
    Points<2> P(2, 3);
    P << 0, 0, 1, 0, 0, 0;
    CHECK(hermite::meanSampleSpacing<2>(P) == doctest::Approx(bruteForceSpacing<2>(P)));
  }
}

TEST_CASE("samples: meanSampleSpacing edge cases and speed") {
  CHECK(hermite::meanSampleSpacing<3>(Points<3>(3, 0)) == 0.0);
  CHECK(hermite::meanSampleSpacing<3>(Points<3>::Zero(3, 1)) == 0.0);
  CHECK(hermite::meanSampleSpacing<2>(Points<2>::Ones(2, 5)) == 0.0);  // all coincide

  // 1e5 samples on a sphere: the grid hash is O(N); an O(N²) search would make this test slow.
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0, 1);
  Points<3> P(3, 100000);
  for (int i = 0; i < P.cols(); ++i) P.col(i) = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  const auto start = std::chrono::steady_clock::now();
  const double spacing = hermite::meanSampleSpacing<3>(P);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Random points on the unit sphere: mean nearest distance ≈ 0.5·sqrt(4π/N) (Poisson process).
  CHECK(spacing == doctest::Approx(0.5 * std::sqrt(4 * M_PI / double(P.cols()))).epsilon(0.05));
  CHECK(seconds < 5.0);
}
