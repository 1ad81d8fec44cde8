#pragma once
// Degenerate fields (docs/maths.md, "Degenerate fields"): with a compact or decaying kernel, no
// polynomial and a small r, f ≈ 0 away from the data, and the sign of that ≈ 0 — which decides
// the zero set there — is noise. A point x is flat when both its value and its slope are below a
// small fraction τ of the data's scale:
//     |f(x)| / (g·h) + ‖∇f(x)‖ / g < τ,
// with g the median ‖∇f(pᵢ)‖ over the samples (≈ 1: the normals are unit) and h their mean
// nearest-neighbour spacing. Near the true zero set ‖∇f‖ ≈ g, so the real surface is never flat.
// The field is degenerate when the flat points are a large part of a grid over the bounds.

#include <cmath>
#include <string>

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "core/points/hermite_samples.h"

namespace hermite {

struct DegenerateFieldOptions {
  int resolution = 0;               // grid cells along the longest side; 0: 200 in 2D, 40 in 3D
  double tolerance = 1e-6;          // τ
  // Degenerate when more than this fraction of the grid is flat: wendland_sphere6_r1_none (43 %,
  // a speckled box in the GPU view, a false inner surface in the mesh) is, the well-posed teaching
  // scenes (at most 17 %: wendland_twotori_120pts_r1_none) are not.
  double largeFraction = 0.25;
};

// The scale a field is judged by, and whether x is flat on it.
struct FlatnessScale {
  double gradient = 0;  // g: median ‖∇f(pᵢ)‖
  double spacing = 0;   // h
  double tolerance = 0; // τ
  bool flat(double f, double gradNorm) const {
    return std::abs(f) / (gradient * spacing) + gradNorm / gradient < tolerance;
  }
};

template <int Dim>
FlatnessScale flatnessScale(const ImplicitField<Dim>& field, const HermiteSamples<Dim>& samples, double tolerance);

// How the warning of DegenerateFieldReport::message() begins (callers pick it out of a fit's warnings).
inline constexpr const char* kDegenerateFieldWarningStart = "degenerate field:";

struct DegenerateFieldReport {
  double flatFraction = 0;  // of the grid points (where the field has data)
  FlatnessScale scale;
  bool degenerate = false;
  // The warning (cause and remedy), "" when not degenerate.
  std::string message() const;
};

// Samples f and ∇f on a grid over `box`; samples.size() ≥ 1.
template <int Dim>
DegenerateFieldReport detectDegenerateField(const ImplicitField<Dim>& field, const Box<Dim>& box,
                                            const HermiteSamples<Dim>& samples, const DegenerateFieldOptions& options = {});

}  // namespace hermite
