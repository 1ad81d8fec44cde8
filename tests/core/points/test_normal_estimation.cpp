#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/base/errors.h"
#include "core/points/normal_estimation.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/mesh_shapes.h"
#include "support/mesh_samples.h"
#include "support/test_data.h"

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
  const double thickness = 2.5 * spacing;
  TriMesh outer = uvSphereMesh(256, 128);
  TriMesh inner = outer;
  inner.vertices *= 1 - thickness;
  inner.triangles.row(1).swap(inner.triangles.row(2));  // counter-clockwise seen from the hollow
  TriMesh shell;
  shell.vertices.resize(3, outer.vertexCount() + inner.vertexCount());
  shell.vertices << outer.vertices, inner.vertices;
  shell.triangles.resize(3, outer.triangleCount() + inner.triangleCount());
  shell.triangles << outer.triangles, (inner.triangles.array() + outer.vertexCount()).matrix();
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
