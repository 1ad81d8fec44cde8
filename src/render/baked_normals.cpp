#include "render/baked_normals.h"

#include <algorithm>
#include <cmath>

#include "core/trace/shading.h"

namespace hermite::render {

std::vector<std::uint8_t> bakedNormalTexels(const VolumeBake& bake) {
  const int R = bake.resolution;
  const Vec<3> h = bake.spacing();
  std::vector<std::uint8_t> texels(4 * std::size_t(R) * R * R);
#pragma omp parallel for schedule(static)
  for (int k = 0; k < R; ++k)
    for (int j = 0; j < R; ++j)
      for (int i = 0; i < R; ++i) {
        // (f(x + h) − f(x − h)) / 2h per axis, neighbours clamped to the grid.
        const Vec<3> g((double(bake.value(std::min(i + 1, R - 1), j, k)) - bake.value(std::max(i - 1, 0), j, k)) / h.x(),
                       (double(bake.value(i, std::min(j + 1, R - 1), k)) - bake.value(i, std::max(j - 1, 0), k)) / h.y(),
                       (double(bake.value(i, j, std::min(k + 1, R - 1))) - bake.value(i, j, std::max(k - 1, 0))) / h.z());
        const double norm = g.norm();
        const Vec<3> n = (norm > 0 && std::isfinite(norm)) ? Vec<3>(g / norm) : Vec<3>::Zero();
        const std::size_t at = i + std::size_t(R) * (j + std::size_t(R) * k);
        std::uint8_t* t = &texels[4 * at];
        for (int c = 0; c < 3; ++c) t[c] = shading::toByte((n(c) + 1.0) * 0.5);
        t[3] = !bake.noData.empty() && bake.noData[at] ? 0 : 255;
      }
  return texels;
}

Vec<3> decodeBakedNormal(const std::uint8_t* texel) {
  return Vec<3>(2.0 * texel[0] / 255.0 - 1.0, 2.0 * texel[1] / 255.0 - 1.0, 2.0 * texel[2] / 255.0 - 1.0);
}

}  // namespace hermite::render
