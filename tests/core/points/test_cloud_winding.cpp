// The winding number of an oriented point cloud (cloud_winding.h): about 1 inside a densely
// sampled closed surface, 0 outside, ½ on it; the sign follows the normals; the batch and the
// single evaluation agree.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/points/cloud_winding.h"
#include "core/shapes/presets.h"
#include "support/mesh_samples.h"

using namespace hermite;

TEST_CASE("winding number of a sampled sphere: 1 inside, 0 outside, about 1/2 on it") {
  const HermiteSamples<3> s = makePreset3d("sphere", 4000);
  const CloudWinding<3> w(s.points, s.normals);
  CHECK(w.size() == 4000);
  // Spacing about √(4π/4000) = 0.056: from two spacings off the sphere on, the side is clear;
  // the areas of a lattice-like sampling are within 15 % (cloud_winding.h).
  for (const Vec<3>& inside : {Vec<3>(0, 0, 0), Vec<3>(0.5, 0.2, -0.1), Vec<3>(0, 0, 0.9)})
    CHECK(std::abs(w.at(inside) - 1.0) < 0.15);
  for (const Vec<3>& outside : {Vec<3>(2, 0, 0), Vec<3>(0.7, 0.7, 0.7), Vec<3>(0, -1.1, 0), Vec<3>(30, 5, 0)})
    CHECK(std::abs(w.at(outside)) < 0.15);
  for (int i = 0; i < 4000; i += 397) {  // on the surface, between the samples or at one
    const Vec<3> p = s.points.col(i);
    CHECK(w.at(p) > 0.3);
    CHECK(w.at(p) < 0.7);
  }
  const CloudWinding<3> flipped(s.points, -s.normals);
  CHECK(std::abs(flipped.at(Vec<3>(0.1, 0, 0)) + 1.0) < 0.15);
}

TEST_CASE("winding number: the batch equals the single evaluation") {
  const HermiteSamples<3> s = makePreset3d("torus", 3000);
  const CloudWinding<3> w(s.points, s.normals);
  Points<3> X(3, 5);
  X << 0.7, 0, 0, 2, 0.9,  //
      0, 0.7, 0, 0, 0.1,     //
      0, 0, 0, 0.3, 0.2;     // columns: in the tube, in the tube, in the hole, outside, in the tube
  const std::vector<double> batch = w.at(X);
  for (int i = 0; i < 5; ++i) CHECK(batch[static_cast<std::size_t>(i)] == w.at(Vec<3>(X.col(i))));
  CHECK(std::abs(batch[0] - 1.0) < 0.15);  // the tube (R = 0.7, r = 0.3) sampled in staggered rings
  CHECK(std::abs(batch[1] - 1.0) < 0.15);
  CHECK(std::abs(batch[2]) < 0.15);
  CHECK(std::abs(batch[3]) < 0.15);
}

TEST_CASE("winding number: the far field stays near the direct sum beside the surface, sharp edges included") {
  // A box sampled uniformly by area (spacing about 0.02), and points up to 3 spacings off it along
  // the samples' normals, and a sampled circle likewise: the first-order far field was off by 0.083
  // (3D) and 0.068 (2D) here, the second-order one by 0.016 and 0.028.
  const HermiteSamples<3> box = testing::sampleMesh(testing::boxMesh(Vec<3>::Zero(), Vec<3>(1, 0.6, 0.4)), 6000, 5);
  const HermiteSamples<2> circle = makePreset2d("circle", 2000);
  const CloudWinding<3> w(box.points, box.normals);
  const CloudWinding<2> w2(circle.points, circle.normals);
  double worst = 0, worst2 = 0;
  for (int i = 0; i < 6000; i += 13) {
    const double off = 0.02 * (3.0 * ((i / 13) % 13) / 6.0 - 3.0);  // −3 … 3 spacings
    const Vec<3> x = box.points.col(i) + off * box.normals.col(i);
    worst = std::max(worst, std::abs(w.at(x) - w.directAt(x)));
    const Vec<2> y = circle.points.col(i % 2000) * (1 + 0.5 * off);
    worst2 = std::max(worst2, std::abs(w2.at(y) - w2.directAt(y)));
  }
  MESSAGE("far field against the direct sum: 3D ", worst, ", 2D ", worst2);
  CHECK(worst < 0.03);
  CHECK(worst2 < 0.04);
}

TEST_CASE("winding number of a sampled circle in 2D") {
  const HermiteSamples<2> s = makePreset2d("circle", 400);
  const CloudWinding<2> w(s.points, s.normals);
  CHECK(std::abs(w.at(Vec<2>(0, 0)) - 1.0) < 0.05);
  CHECK(std::abs(w.at(Vec<2>(0.6, -0.3)) - 1.0) < 0.05);
  CHECK(std::abs(w.at(Vec<2>(1.5, 0))) < 0.05);
  CHECK(std::abs(w.at(Vec<2>(-3, 4))) < 0.05);
}

TEST_CASE("winding number: samples without one normal each are refused") {
  const HermiteSamples<3> s = makePreset3d("sphere", 100);
  CHECK_THROWS(CloudWinding<3>(s.points, Points<3>(3, 99)));
  CHECK_THROWS(CloudWinding<3>(Points<3>(3, 0), Points<3>(3, 0)));
}
