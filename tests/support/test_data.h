#pragma once
// Small deterministic data sets for the core tests (independent of the presets under test).

#include <cmath>

#include "core/points/hermite_samples.h"

namespace hermite::testing {

// N points on the unit sphere by the golden spiral, normals = points.
inline HermiteSamples<3> goldenSphere(int N, double radius = 1.0) {
  HermiteSamples<3> s;
  s.points.resize(3, N);
  s.normals.resize(3, N);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < N; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / N;
    const double rho = std::sqrt(1.0 - z * z);
    const Vec<3> n(rho * std::cos(golden * i), rho * std::sin(golden * i), z);
    s.normals.col(i) = n;
    s.points.col(i) = radius * n;
  }
  return s;
}

// N points on the ellipse x²/a² + y²/b² = 1 with exact outward normals.
inline HermiteSamples<2> ellipse(int N, double a = 1.0, double b = 0.6) {
  HermiteSamples<2> s;
  s.points.resize(2, N);
  s.normals.resize(2, N);
  for (int i = 0; i < N; ++i) {
    const double t = 2.0 * M_PI * i / N;
    s.points.col(i) = Vec<2>(a * std::cos(t), b * std::sin(t));
    s.normals.col(i) = Vec<2>(std::cos(t) / a, std::sin(t) / b).normalized();
  }
  return s;
}

// A non-symmetric 3D blob: golden-spiral directions on r(θ,φ) = 1 + 0.2 z + 0.1 x y; normals
// from the gradient of |x| − r(x/|x|) (exact).
inline HermiteSamples<3> blob(int N) {
  HermiteSamples<3> s = goldenSphere(N);
  for (int i = 0; i < N; ++i) {
    const Vec<3> u = s.normals.col(i);
    const double r = 1.0 + 0.2 * u.z() + 0.1 * u.x() * u.y();
    s.points.col(i) = r * u;
    // F(x) = |x| − R(x/|x|), R(u) = 1 + 0.2 u_z + 0.1 u_x u_y; ∇F = u − (I − u uᵀ)∇R / |x|.
    const Vec<3> gR(0.1 * u.y(), 0.1 * u.x(), 0.2);
    const Vec<3> g = u - (gR - u * u.dot(gR)) / r;
    s.normals.col(i) = g.normalized();
  }
  return s;
}

}  // namespace hermite::testing
