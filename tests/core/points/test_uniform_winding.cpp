// The winding number with every sample standing for the same area (uniform_winding.h): the blocked
// sums equal the formula point by point, and a sampled sphere reads 1 inside, 0 outside.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/points/uniform_winding.h"
#include "core/shapes/presets.h"

using namespace hermite;

namespace {

// The formula, one point at a time.
double plainWinding(const HermiteSamples<3>& s, double spacing, const Vec<3>& x) {
  double sum = 0;
  for (Eigen::Index i = 0; i < s.points.cols(); ++i) {
    const Vec<3> q = s.points.col(i) - x;
    const double r2 = q.squaredNorm() + 0.25 * spacing * spacing;
    sum += q.dot(s.normals.col(i)) / std::pow(r2, 1.5);
  }
  return spacing * spacing * sum / (4 * M_PI);
}

}  // namespace

TEST_CASE("uniform-area winding: every count of points, in any order, gets the formula's value") {
  const HermiteSamples<3> s = makePreset3d("torus", 3000);
  const double spacing = 0.05;
  Points<3> X = Points<3>::Random(3, 40) * 1.5;
  for (int count : {1, 7, 8, 9, 17, 40}) {  // partial and whole blocks of points
    std::vector<Eigen::Index> cols;
    for (int k = 0; k < count; ++k) cols.push_back((k * 13) % 40);  // scattered, repeats allowed
    const std::vector<double> w = uniformAreaWinding(s, spacing, X, cols);
    REQUIRE(w.size() == cols.size());
    for (std::size_t k = 0; k < cols.size(); ++k)
      CHECK(std::abs(w[k] - plainWinding(s, spacing, X.col(cols[k]))) <= 1e-12 * (1 + std::abs(w[k])));
  }
  CHECK(uniformAreaWinding(s, spacing, X, {}).empty());
}

TEST_CASE("uniform-area winding of a sampled sphere: 1 inside, 0 outside, the sign follows the normals") {
  const int n = 4000;
  const HermiteSamples<3> s = makePreset3d("sphere", n);
  const double spacing = std::sqrt(4 * M_PI / n);  // √(A / N) of the unit sphere
  Points<3> X(3, 5);
  X << 0, 0.5, 0, 2, 0.7,  //
      0, 0.2, 0, 0, 0.7,     //
      0, -0.1, 0.85, 0, 0.7;
  const std::vector<double> w = uniformAreaWinding(s, spacing, X, {0, 1, 2, 3, 4});
  for (int k : {0, 1, 2}) CHECK(std::abs(w[static_cast<std::size_t>(k)] - 1.0) < 0.05);  // inside
  for (int k : {3, 4}) CHECK(std::abs(w[static_cast<std::size_t>(k)]) < 0.05);  // outside
  HermiteSamples<3> flipped = s;
  flipped.normals = -s.normals;
  CHECK(std::abs(uniformAreaWinding(flipped, spacing, X, {0})[0] + 1.0) < 0.05);
}
