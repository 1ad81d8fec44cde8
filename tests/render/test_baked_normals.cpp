#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>
#include <random>

#include "core/shapes/analytic_shapes.h"
#include "core/trace/volume_bake.h"
#include "render/baked_normals.h"

using namespace hermite;
using namespace hermite::render;

namespace {

double angleDeg(const Vec<3>& a, const Vec<3>& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

// Central difference of the bake's trilinear interpolant one cell apart: what the shader's six
// fetches computed before the normal texture.
Vec<3> interpolantCentralDifference(const VolumeBake& bake, const Vec<3>& x) {
  const Vec<3> h = bake.spacing();
  Vec<3> g;
  for (int k = 0; k < 3; ++k) {
    Vec<3> e = Vec<3>::Zero();
    e(k) = h(k);
    g(k) = (bake.interpolate(x + e) - bake.interpolate(x - e)) / (2 * h(k));
  }
  return g;
}

// The decoded texels as three bakes over the same grid, one per component: their interpolate()
// is the trilinear filtering GL_LINEAR applies to the texture.
std::array<VolumeBake, 3> decodedComponents(const VolumeBake& bake, const std::vector<std::uint8_t>& texels) {
  std::array<VolumeBake, 3> out;
  for (int c = 0; c < 3; ++c) {
    out[c].bounds = bake.bounds;
    out[c].resolution = bake.resolution;
    out[c].values.resize(bake.values.size());
    for (std::size_t q = 0; q < bake.values.size(); ++q)
      out[c].values[q] = float(decodeBakedNormal(&texels[4 * q])(c));
  }
  return out;
}

}  // namespace

TEST_CASE("baked normals: the filtered texture points along the interpolant's central difference") {
  Box<3> bounds;
  bounds.lo = Vec<3>(-1.2, -1.1, -1.3);
  bounds.hi = Vec<3>(1.3, 1.2, 1.1);
  const TorusField torus;
  VolumeBakeOptions options;
  options.resolution = 48;
  const VolumeBake bake = bakeVolume(torus, bounds, options);
  const std::vector<std::uint8_t> texels = bakedNormalTexels(bake);
  REQUIRE(texels.size() == 4 * std::size_t(48) * 48 * 48);

  // At the samples: the stored unit direction, to 8-bit rounding (≤ 1/255 per component).
  std::mt19937 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const int i = int(rng() % 48), j = int(rng() % 48), k = int(rng() % 48);
    const Vec<3> g = interpolantCentralDifference(bake, bake.samplePosition(i, j, k));
    const std::uint8_t* t = &texels[4 * (i + std::size_t(48) * (j + std::size_t(48) * k))];
    CHECK(t[3] == 255);
    if (g.norm() < 1e-9) continue;
    const Vec<3> n = decodeBakedNormal(t);
    CAPTURE(i);
    CAPTURE(j);
    CAPTURE(k);
    CHECK((n - g.normalized()).cwiseAbs().maxCoeff() <= 1.0 / 255.0 + 1e-9);
  }
  // Between samples, near the surface where shading reads it. The two differ by normalising
  // before interpolating (the eight directions weigh alike instead of by their gradient norms:
  // second order in the directions' spread over a cell, which is up to ~10° here, a tube of
  // radius 6 cells) and by the 8-bit storage; the tolerances below bound both.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0;
  int tested = 0;
  std::vector<double> angles;
  const std::array<VolumeBake, 3> components = decodedComponents(bake, texels);
  auto filteredDirection = [&](const Vec<3>& x) {
    return Vec<3>(components[0].interpolate(x), components[1].interpolate(x), components[2].interpolate(x));
  };
  while (tested < 3000) {
    const Vec<3> x = bounds.lo + bounds.extent().cwiseProduct(Vec<3>(unit(rng), unit(rng), unit(rng)));
    if (std::abs(torus.evaluate(x)) > 0.1) continue;
    ++tested;
    angles.push_back(angleDeg(filteredDirection(x), interpolantCentralDifference(bake, x)));
    worst = std::max(worst, angles.back());
  }
  std::sort(angles.begin(), angles.end());
  CHECK(angles[angles.size() / 2] <= 0.25);
  CHECK(angles[angles.size() * 99 / 100] <= 0.5);
  CHECK(worst <= 2.0);
}

TEST_CASE("baked normals: no direction where the samples are flat or not finite") {
  Box<3> bounds;
  bounds.lo = Vec<3>::Constant(-1);
  bounds.hi = Vec<3>::Constant(1);
  VolumeBake bake;
  bake.bounds = bounds;
  bake.resolution = 4;
  bake.values.assign(64, 0.5f);
  bake.values[1 + 4 * (1 + 4 * 1)] = std::numeric_limits<float>::quiet_NaN();
  const std::vector<std::uint8_t> texels = bakedNormalTexels(bake);
  // Flat: sample (3, 3, 3), far from the NaN; its neighbours (0 … 2) see the NaN.
  const std::uint8_t* flat = &texels[4 * (3 + 4 * (3 + 4 * 3))];
  CHECK(decodeBakedNormal(flat).norm() < 0.01);
  const std::uint8_t* nearNan = &texels[4 * (2 + 4 * (1 + 4 * 1))];
  CHECK(decodeBakedNormal(nearNan).norm() < 0.01);
}
