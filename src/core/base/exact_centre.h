#pragma once
// The origin a fit's polynomial part is written about (docs/maths.md, Centring): a point c
// such that every pᵢ − c is exact in double precision, and c = 0 whenever the data's bounding
// box lies near the origin, so data there is fitted exactly as without centring.
//
// Per axis: E = the largest extent of the box over all axes, 2ᵏ the smallest power of two ≥ E,
// c = 2ᵏ·trunc(mid / 2ᵏ) for the box's midpoint mid, and c = 0 where |trunc(mid / 2ᵏ)| < 2.
// Then every coordinate x has the sign of c and 0 < c ≤ 2x, and x − c is a multiple of
// min(ulp(x), 2ᵏ) no larger than max(|x|, 1.5·2ᵏ): representable, so the subtraction is exact.
// The result is checked anyway (x − c + c == x on every axis); an axis that fails gets 0.

#include <cmath>

#include "core/base/geometry.h"

namespace hermite {

template <int Dim>
Vec<Dim> exactCentre(const Points<Dim>& points) {
  Vec<Dim> c = Vec<Dim>::Zero();
  if (points.cols() == 0 || !points.allFinite()) return c;
  const Vec<Dim> lo = points.rowwise().minCoeff(), hi = points.rowwise().maxCoeff();
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0) || !std::isfinite(extent)) return c;  // one point (or identical ones): nothing to gain
  int e = 0;
  const double mantissa = std::frexp(extent, &e);  // extent = mantissa · 2ᵉ, mantissa in [0.5, 1)
  const int k = mantissa == 0.5 ? e - 1 : e;       // 2ᵏ ≥ extent
  for (int a = 0; a < Dim; ++a) {
    const double mid = lo(a) + 0.5 * (hi(a) - lo(a));
    const double j = std::trunc(std::ldexp(mid, -k));
    if (std::abs(j) < 2) continue;
    const double ca = std::ldexp(j, k);
    bool exact = true;
    for (Eigen::Index i = 0; i < points.cols() && exact; ++i) exact = (points(a, i) - ca) + ca == points(a, i);
    if (exact) c(a) = ca;
  }
  return c;
}

}  // namespace hermite
