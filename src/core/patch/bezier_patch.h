#pragma once
// Bicubic Bézier patch: 4 × 4 control points P[i][j] (i along s, j along t), evaluated by de
// Casteljau, subdivided, and converted exactly to and from the Hermite form (hermite_patch.h).
//
// Conversion, per direction, from Hermite data (P0, P0′, P1′, P1) to Bézier points (b0..b3):
// b0 = P0, b1 = P0 + P0′/3, b2 = P1 − P1′/3, b3 = P1 — the matrix M below — so the tensor patch
// has B = M C Mᵀ per coordinate, and C = M⁻¹ B M⁻ᵀ back. Both forms are the same polynomial.

#include <array>
#include <utility>

#include "core/patch/hermite_patch.h"

namespace hermite {

struct BezierPatch {
  std::array<std::array<Vec<3>, 4>, 4> P;  // P[i][j]: i along s, j along t

  // de Casteljau in t on each row, then in s; derivatives from the last-but-one level.
  SurfacePoint evaluate(double s, double t) const;
  // Splits at s (two patches covering [0, s] and [s, 1] in s) or at t.
  std::pair<BezierPatch, BezierPatch> splitS(double s) const;
  std::pair<BezierPatch, BezierPatch> splitT(double t) const;
};

BezierPatch toBezier(const HermitePatch& h);
HermitePatch toHermite(const BezierPatch& b);

// The 4 × 4 change of basis Hermite (P0, P0′, P1′, P1) → Bézier (b0, b1, b2, b3), and back.
const Eigen::Matrix4d& hermiteToBezierMatrix();
const Eigen::Matrix4d& bezierToHermiteMatrix();

}  // namespace hermite
