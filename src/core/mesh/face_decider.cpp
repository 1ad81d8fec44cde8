#include "core/mesh/face_decider.h"

#include <algorithm>
#include <cmath>

namespace hermite::detail {

namespace {

// The face's corner point indices: its lowest point, then +u, +w and +u+w, where u and w are the
// two axes after its normal axis a (cyclically).
std::array<std::int64_t, 4> faceCorners(const MarchingGrid<3>& g, std::int64_t key) {
  const std::int64_t p = key / 3;
  const int a = static_cast<int>(key % 3), u = (a + 1) % 3, w = (a + 2) % 3;
  return {p, p + g.stride[u], p + g.stride[w], p + g.stride[u] + g.stride[w]};
}

// The bilinear interpolant's saddle point on the face (ambiguous: its denominator is non-zero).
Vec<3> saddlePoint(const MarchingGrid<3>& g, std::int64_t key) {
  const std::array<std::int64_t, 4> c = faceCorners(g, key);
  const double f00 = g.values[c[0]], f10 = g.values[c[1]], f01 = g.values[c[2]], f11 = g.values[c[3]];
  const double d = f00 - f10 - f01 + f11;
  const int a = static_cast<int>(key % 3), u = (a + 1) % 3, w = (a + 2) % 3;
  const std::array<int, 3> at = g.coords(c[0]);
  Vec<3> x = g.point(c[0]);
  x[u] += std::clamp((f00 - f01) / d, 0.0, 1.0) * g.step(u, at[u]);
  x[w] += std::clamp((f00 - f10) / d, 0.0, 1.0) * g.step(w, at[w]);
  return x;
}

}  // namespace

int FaceDecisions::lookup(std::int64_t key) const {
  const auto it = std::lower_bound(keys.begin(), keys.end(), key);
  if (it == keys.end() || *it != key) return -1;
  return outsideConnected[static_cast<std::size_t>(it - keys.begin())];
}

bool ambiguousFace(const MarchingGrid<3>& g, std::int64_t key) {
  const std::array<std::int64_t, 4> c = faceCorners(g, key);
  for (std::int64_t p : c)
    if (!g.isValid(p)) return false;
  const bool s00 = g.inside(c[0]), s10 = g.inside(c[1]), s01 = g.inside(c[2]), s11 = g.inside(c[3]);
  return s00 == s11 && s10 == s01 && s00 != s10;
}

FaceDecisions decideAmbiguousFaces(const MarchingGrid<3>& g, const ImplicitField<3>& field,
                                   const std::vector<std::int64_t>& cells, const CancelToken* cancel) {
  FaceDecisions d;
  for (std::int64_t origin : cells)
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        const std::int64_t key = 3 * (origin + side * g.stride[a]) + a;
        if (ambiguousFace(g, key)) d.keys.push_back(key);
      }
  std::sort(d.keys.begin(), d.keys.end());
  d.keys.erase(std::unique(d.keys.begin(), d.keys.end()), d.keys.end());
  d.outsideConnected.assign(d.keys.size(), -1);
  if (d.keys.empty()) return d;
  Points<3> X(3, static_cast<Eigen::Index>(d.keys.size()));
  for (std::size_t i = 0; i < d.keys.size(); ++i) X.col(static_cast<Eigen::Index>(i)) = saddlePoint(g, d.keys[i]);
  Eigen::VectorXd f;
  Points<3> G;
  evaluateChunked<3>(field, X, f, G, cancel);
  for (std::size_t i = 0; i < d.keys.size(); ++i) {
    const double fi = f[static_cast<Eigen::Index>(i)];
    if (std::isfinite(fi)) d.outsideConnected[i] = fi >= 0 ? 1 : 0;
  }
  return d;
}

}  // namespace hermite::detail
