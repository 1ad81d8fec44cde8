#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <random>

#include "core/base/errors.h"
#include "core/points/normal_estimation.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/mesh_shapes.h"
#include "support/mesh_samples.h"
#include "support/test_data.h"
#include "support/thin_shapes.h"

using namespace hermite;

TEST_CASE("normal estimation: a sphere cloud gets outward unit normals") {
  const HermiteSamples<3> s = testing::goldenSphere(2000, 0.8);
  const Points<3> n = estimateNormals<3>(s.points);
  double worst = 1;
  for (int i = 0; i < s.size(); ++i) {
    CHECK(n.col(i).norm() == doctest::Approx(1.0).epsilon(1e-12));
    worst = std::min(worst, n.col(i).dot(s.normals.col(i)));
  }
  CHECK(worst > std::cos(5.0 * M_PI / 180));  // within 5° of the exact normal, all outward
}

TEST_CASE("normal estimation: a torus cloud and two separate components are oriented consistently") {
  // Area-uniform random torus points (R = 0.7, r = 0.3) and a far sphere: two components.
  const TorusField torus;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 2 * M_PI), v(0, 1);
  const int nt = 3000, ns = 500;
  Points<3> P(3, nt + ns), exact(3, nt + ns);
  for (int i = 0; i < nt;) {
    const double a = u(rng), b = u(rng);
    if (v(rng) > (0.7 + 0.3 * std::cos(b)) / 1.0) continue;
    const Vec<3> p((0.7 + 0.3 * std::cos(b)) * std::cos(a), (0.7 + 0.3 * std::cos(b)) * std::sin(a), 0.3 * std::sin(b));
    P.col(i) = p;
    exact.col(i) = torus.gradient(p).normalized();
    ++i;
  }
  const HermiteSamples<3> sphere = testing::goldenSphere(ns, 0.5);
  for (int i = 0; i < ns; ++i) {
    P.col(nt + i) = sphere.points.col(i) + Vec<3>(3, 0, 0);
    exact.col(nt + i) = sphere.normals.col(i);
  }
  const Points<3> n = estimateNormals<3>(P);
  int wrong = 0;
  double sumCos = 0;
  for (int i = 0; i < P.cols(); ++i) {
    const double c = n.col(i).dot(exact.col(i));
    if (c < 0) ++wrong;
    sumCos += c;
  }
  CHECK(wrong == 0);
  CHECK(sumCos / P.cols() > 0.99);
}

TEST_CASE("normal estimation: a 2D circle, flipping, and too few points") {
  const HermiteSamples<2> c = testing::ellipse(200, 1.0, 1.0);
  Points<2> n = estimateNormals<2>(c.points);
  for (int i = 0; i < c.size(); ++i) CHECK(n.col(i).dot(c.normals.col(i)) > 0.999);
  flipNormals<2>(n);
  for (int i = 0; i < c.size(); ++i) CHECK(n.col(i).dot(c.normals.col(i)) < -0.999);
  CHECK_THROWS_AS(estimateNormals<2>(Points<2>::Zero(2, 1)), InputError);
}

// Thin parts: two sheets 2.5 sample spacings apart, well inside one another's neighbourhood (the
// 10 nearest neighbours reach about 1.8 spacings, so a neighbourhood 3.6 spacings across spans
// both sheets and the k-NN graph links them). A tree that copies orientations across the gap
// flips a whole sheet (half the normals); the estimate keeps at most 0.5 % against the truth.
TEST_CASE("normal estimation: a thin slab keeps both sheets oriented outward") {
  const int n = 20000;
  const double spacing = std::sqrt(2.0 / n);  // the slab's area is ≈ 2 (two unit squares)
  const double thickness = 2.5 * spacing;
  const HermiteSamples<3> slab =
      testing::sampleMesh(testing::boxMesh(Vec<3>(0, 0, 0), Vec<3>(1, 1, thickness)), n, 7);
  CHECK(meanSampleSpacing<3>(slab.points) < thickness);
  const Points<3> estimated = estimateNormals<3>(slab.points);
  CHECK(testing::flippedFraction(estimated, slab.normals) <= 0.005);
}

TEST_CASE("normal estimation: a hollow ball's inner sheet points inward, across the gap from the outer") {
  // The solid between spheres of radius 1 and 1 − t: outward normals outside, inward inside.
  const int n = 40000;
  const double spacing = std::sqrt(8 * M_PI / n);  // the two spheres' area ≈ 8π
  const TriMesh shell = testing::hollowBall(2.5 * spacing);
  const HermiteSamples<3> s = testing::sampleMesh(shell, n, 11);
  const Points<3> estimated = estimateNormals<3>(s.points);
  CHECK(testing::flippedFraction(estimated, s.normals) <= 0.005);
}

TEST_CASE("normal estimation: zero normals are filled and follow the given ones") {
  const HermiteSamples<3> s = testing::goldenSphere(1500, 1.0);
  // Every fifth normal missing, the others given inward: the filled ones point inward too.
  Points<3> normals = -s.normals;
  for (int i = 0; i < s.size(); i += 5) normals.col(i).setZero();
  const Points<3> given = normals;
  CHECK(completeNormals<3>(s.points, normals) == 300);
  for (int i = 0; i < s.size(); ++i) {
    if (i % 5 == 0) CHECK(normals.col(i).dot(s.normals.col(i)) < -0.99);
    else CHECK(normals.col(i) == given.col(i));  // kept as given
  }
  Points<3> complete = s.normals;
  CHECK(completeNormals<3>(s.points, complete) == 0);
  Points<3> lone = Points<3>::Zero(3, 1);
  CHECK_THROWS_AS(completeNormals<3>(Points<3>::Zero(3, 1), lone), InputError);
}

// The slab curled through 270°: both sheets 2.5 spacings apart, bent, so that a seed's outward
// direction has to travel round the curl and along the thin rims.
TEST_CASE("normal estimation: a thin curled plate keeps both sheets oriented outward") {
  const int n = 20000;
  const HermiteSamples<3> s = testing::sampleMesh(testing::curledPlate(2.5 * std::sqrt(2.0 / n)), n, 3);
  CHECK(testing::flippedFraction(estimateNormals<3>(s.points), s.normals) <= 0.005);
}

namespace {

// The true normal lines of `s` with signs from `sign(i, n)` (±1).
template <class Sign>
Points<3> signedLines(const HermiteSamples<3>& s, Sign sign) {
  Points<3> lines = s.normals;
  for (int i = 0; i < s.size(); ++i) lines.col(i) *= sign(i, Vec<3>(s.normals.col(i)));
  return lines;
}

}  // namespace

// CGAL's cube.pwn: a box-like part whose normals are lines with the sign that makes their
// largest component positive, so one face of each pair points inward; and the same lines with
// random signs, which the check flags (a plain box with canonical signs disagrees only across
// its creases, which the check leaves out). Re-orienting keeps the lines and makes ≤ 0.5 % point
// against the truth (sharp 90° creases: the crease rule, not a sign copied across perpendicular
// normals).
TEST_CASE("normal orientation: box samples with unoriented normals are detected and re-oriented") {
  const HermiteSamples<3> s =
      testing::sampleMesh(testing::boxMesh(Vec<3>(-0.5, -0.37, -0.37), Vec<3>(0.5, 0.37, 0.37)), 20000, 5);
  CHECK(orientationDisagreement<3>(s.points, s.normals) <= 0.005);
  std::mt19937 rng(9);
  const Points<3> canonical = signedLines(s, [](int, const Vec<3>& n) {
    Eigen::Index axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    return n(axis) < 0 ? -1.0 : 1.0;
  });
  const Points<3> random = signedLines(s, [&](int, const Vec<3>&) { return rng() & 1 ? -1.0 : 1.0; });
  CHECK(orientationDisagreement<3>(s.points, random) > 0.1);
  for (const Points<3>& given : {canonical, random}) {
    Points<3> oriented = given;
    const int changed = orientNormalLines<3>(s.points, oriented);
    CHECK(testing::flippedFraction(oriented, s.normals) <= 0.005);
    CHECK(orientationDisagreement<3>(s.points, oriented) <= 0.005);
    int counted = 0;
    for (int i = 0; i < s.size(); ++i) {
      CHECK(std::abs(oriented.col(i).dot(given.col(i))) == doctest::Approx(1.0).epsilon(1e-12));  // the same line
      counted += oriented.col(i).dot(given.col(i)) < 0;
    }
    CHECK(changed == counted);
  }
}

TEST_CASE("normal orientation: a thin slab's unoriented lines are re-oriented outward") {
  const int n = 20000;
  const HermiteSamples<3> s =
      testing::sampleMesh(testing::boxMesh(Vec<3>(0, 0, 0), Vec<3>(1, 1, 2.5 * std::sqrt(2.0 / n))), n, 7);
  std::mt19937 rng(2);
  Points<3> oriented = signedLines(s, [&](int, const Vec<3>&) { return rng() & 1 ? -1.0 : 1.0; });
  orientNormalLines<3>(s.points, oriented);
  CHECK(testing::flippedFraction(oriented, s.normals) <= 0.005);
}

TEST_CASE("normal orientation: consistent normals pass the check and keep their signs, inward too") {
  const HermiteSamples<3> sphere = testing::goldenSphere(3000, 1.0);
  const Points<3> inward = -sphere.normals;
  CHECK(orientationDisagreement<3>(sphere.points, inward) == 0.0);
  Points<3> oriented = inward;
  CHECK(orientNormalLines<3>(sphere.points, oriented) == 0);
  CHECK(oriented == inward);
  Points<3> withZero = inward;
  withZero.col(4).setZero();
  CHECK_THROWS_AS(orientNormalLines<3>(sphere.points, withZero), InputError);
}

// Sheets closer than the neighbourhood (docs/maths.md, Normal estimation): at 1.5 and 1.0 sample
// spacings the 10 nearest neighbours of a point hold both sheets, often more of the other one;
// plain PCA then tilts or lies in the plane, and one edge between two bad normals used to copy
// an orientation across the gap and turn a whole sheet over (≈ 50 % flipped).
TEST_CASE("normal estimation: a hollow ball whose sheets are 1.5 and 1.0 spacings apart") {
  const int n = 20000;
  const double spacing = std::sqrt(8 * M_PI / n);  // the two spheres' area ≈ 8π
  for (double gap : {1.5, 1.0}) {
    CAPTURE(gap);
    const HermiteSamples<3> s = testing::sampleMesh(testing::hollowBall(gap * spacing), n, 11);
    CHECK(testing::flippedFraction(estimateNormals<3>(s.points), s.normals) <= 0.005);
  }
}

TEST_CASE("normal estimation: a slab 1.5 spacings thick keeps both sheets oriented outward") {
  const int n = 20000;
  const double thickness = 1.5 * std::sqrt(2.0 / n);
  const HermiteSamples<3> s = testing::sampleMesh(testing::boxMesh(Vec<3>(0, 0, 0), Vec<3>(1, 1, thickness)), n, 7);
  CHECK(testing::flippedFraction(estimateNormals<3>(s.points), s.normals) <= 0.005);
}

namespace {

// The flipped fraction among the samples whose true normal is within 60° of `axis` (one sheet).
double sheetFlipped(const HermiteSamples<3>& s, const Points<3>& estimated, const std::function<Vec<3>(int)>& axis) {
  int count = 0, flipped = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (s.normals.col(i).dot(axis(i)) < 0.5) continue;
    ++count;
    flipped += estimated.col(i).dot(s.normals.col(i)) < 0;
  }
  return count == 0 ? 1.0 : double(flipped) / count;
}

// The flipped fraction among the samples of the rims: whose true normal is within 30° of the
// sheets' plane (⊥ `axis(i)`, the sheets' normal line at sample i).
double rimFlipped(const HermiteSamples<3>& s, const Points<3>& estimated, const std::function<Vec<3>(int)>& axis) {
  int count = 0, flipped = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (std::abs(s.normals.col(i).dot(axis(i))) > 0.5) continue;
    ++count;
    flipped += estimated.col(i).dot(s.normals.col(i)) < 0;
  }
  return count == 0 ? 1.0 : double(flipped) / count;
}

}  // namespace

// Closer still, at 1.5 and 1.0 spacings the slab's and the curled plate's rims are faces only 1–1.5
// spacings wide between the sheets, whose samples the sheet fit gives the sheets' normal line:
// the fold rule (docs/maths.md, Folds) gives them the rim's direction, and their samples, not
// trusted, no longer join the two sheets in one patch. Before it: 1.0–2.3 % flipped here, most on
// and beside the rims (≈ half of the rims' samples); after, ≤ 0.33 % over seeds 1, 3, 7 and 11.
// Each sheet, outward and inward, and all samples are checked against 0.5 %, the rims' samples
// against 12 % (measured 2.3–7.9 % here; ≈ 23 % before, their signs a coin toss).
TEST_CASE("normal estimation: a slab 1.0 and 1.5 spacings thick, rims included, keeps 99.5 % oriented outward") {
  const int n = 20000;
  for (double gap : {1.0, 1.5}) {
    CAPTURE(gap);
    const HermiteSamples<3> slab =
        testing::sampleMesh(testing::boxMesh(Vec<3>(0, 0, 0), Vec<3>(1, 1, gap * std::sqrt(2.0 / n))), n, 7);
    const Points<3> ns = estimateNormals<3>(slab.points);
    const auto up = [](int) { return Vec<3>(0, 0, 1); };
    CHECK(testing::flippedFraction(ns, slab.normals) <= 0.005);
    CHECK(sheetFlipped(slab, ns, up) <= 0.005);
    CHECK(sheetFlipped(slab, ns, [](int) { return Vec<3>(0, 0, -1); }) <= 0.005);
    CHECK(rimFlipped(slab, ns, up) <= 0.12);
  }
}

TEST_CASE("normal estimation: a curled plate 1.0 and 1.5 spacings thick, rims included, keeps 99.5 % oriented outward") {
  const int n = 20000;
  for (double gap : {1.0, 1.5}) {
    CAPTURE(gap);
    const HermiteSamples<3> curl = testing::sampleMesh(testing::curledPlate(gap * std::sqrt(2.0 / n)), n, 3);
    const Points<3> nc = estimateNormals<3>(curl.points);
    auto radial = [&](int i) { return Vec<3>(curl.points(0, i), 0, curl.points(2, i)).normalized().eval(); };
    CHECK(testing::flippedFraction(nc, curl.normals) <= 0.005);
    CHECK(sheetFlipped(curl, nc, radial) <= 0.005);
    CHECK(sheetFlipped(curl, nc, [&](int i) { return (-radial(i)).eval(); }) <= 0.005);
    CHECK(rimFlipped(curl, nc, radial) <= 0.12);
  }
}

// A thin void: the same slab with every normal given inward, a fifth of them given and the rest
// zero. Its rims are then concave folds (the surface of a slot), whose normals point into the
// void, towards the sheets; the filled normals follow the given ones there too.
TEST_CASE("normal estimation: a slab-shaped void 1.0 spacing thick, a fifth of its normals given, is filled inward") {
  const int n = 20000;
  const HermiteSamples<3> slab =
      testing::sampleMesh(testing::boxMesh(Vec<3>(0, 0, 0), Vec<3>(1, 1, std::sqrt(2.0 / n))), n, 5);
  Points<3> normals = Points<3>::Zero(3, n);
  for (int i = 0; i < n; i += 5) normals.col(i) = -slab.normals.col(i);
  CHECK(completeNormals<3>(slab.points, normals) == n - n / 5);
  const Points<3> inward = -slab.normals;
  CHECK(testing::flippedFraction(normals, inward) <= 0.005);
  CHECK(rimFlipped(slab, -normals, [](int) { return Vec<3>(0, 0, 1); }) <= 0.12);
}
