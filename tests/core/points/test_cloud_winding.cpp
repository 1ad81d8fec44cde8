// The winding number of an oriented point cloud (cloud_winding.h): about 1 inside a densely
// sampled closed surface, 0 outside, ½ on it; the sign follows the normals; the batch and the
// single evaluation agree.

#include <doctest/doctest.h>

#include <cmath>

#include "core/points/cloud_winding.h"
#include "core/shapes/presets.h"

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
