#pragma once
// The weight of one support in the smooth blend (docs/maths.md, Partition of unity): the C² bump
// Π_d (1 − t_d²)³ of the coordinates t_d ∈ [−1, 1] across the support box. Internal to the PU
// fit and model.

#include "core/base/geometry.h"

namespace hermite::detail {

// max over t ∈ [−1, 1] of |d/dt (1 − t²)³| = |6t(1 − t²)²|, reached at t = 1/√5.
constexpr double kMaxBumpSlope = 6.0 / 2.2360679774997896964 * 0.64;

// The C² bump of one support at y, with ∇ and Hessian in y coordinates when asked; axes in
// `frozen` (y clamped there) have zero derivatives. Returns 0 outside the support.
template <int Dim>
double bump(const Box<Dim>& support, const Vec<Dim>& y, const bool* frozen, Vec<Dim>* g, Mat<Dim>* H) {
  double b[Dim], db[Dim], d2b[Dim];
  for (int k = 0; k < Dim; ++k) {
    const double h = 0.5 * (support.hi(k) - support.lo(k));
    const double t = (y(k) - 0.5 * (support.hi(k) + support.lo(k))) / h;
    const double u = 1.0 - t * t;
    if (!(u > 0)) return 0.0;
    b[k] = u * u * u;
    db[k] = frozen[k] ? 0.0 : -6.0 * t * u * u / h;
    d2b[k] = frozen[k] ? 0.0 : u * (30.0 * t * t - 6.0) / (h * h);
  }
  double w = 1.0;
  for (int k = 0; k < Dim; ++k) w *= b[k];
  if (g) {
    for (int k = 0; k < Dim; ++k) {
      double p = db[k];
      for (int j = 0; j < Dim; ++j)
        if (j != k) p *= b[j];
      (*g)(k) = p;
    }
  }
  if (H) {
    for (int k = 0; k < Dim; ++k)
      for (int l = 0; l < Dim; ++l) {
        double p = (k == l) ? d2b[k] : db[k] * db[l];
        for (int j = 0; j < Dim; ++j)
          if (j != k && j != l) p *= b[j];
        (*H)(k, l) = p;
      }
  }
  return w;
}

}  // namespace hermite::detail
