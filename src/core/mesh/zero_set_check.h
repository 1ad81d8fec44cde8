#pragma once
// Whether a fitted field's zero set looks like the shape its samples describe (docs/maths.md,
// "Suggesting r"): the zero set is contoured over a box (2D: marching squares curves; 3D:
// marching cubes surfaces at a modest grid) and its components counted; a component that passes
// near no sample is spurious (the data do not support it). Each sample is also pushed along its
// normal: f(p + εn) > 0 and f(p − εn) < 0 must hold (outside and inside where the normal says).
// Last, the field must not be degenerate (degenerate_field.h): where it is flat, its zero set is
// noise even when every component touches a sample.

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "core/mesh/degenerate_field.h"
#include "core/points/hermite_samples.h"

namespace hermite {

struct ZeroSetCheckOptions {
  // Cells along the box's longest side; 0 picks 200 in 2D (curves are cheap) and 40 in 3D
  // (a component count, not a surface to look at).
  int resolution = 0;
  // ε = pushFraction × the samples' mean nearest-neighbour spacing h: far enough that the
  // check is not the interpolation condition ∇f(p) = n restated, near enough that a neighbouring
  // part of the shape (two-tori tubes lie ≈ h apart) is not reached.
  double pushFraction = 0.25;
  DegenerateFieldOptions degenerate;  // its resolution follows `resolution`
};

struct ZeroSetCheck {
  int components = 0;    // curves (2D) or surfaces (3D) of the zero set inside the box
  int spurious = 0;      // of those, the ones within `supportDistance` of no sample
  int signFailures = 0;  // samples with f(p + εn) ≤ 0 or f(p − εn) ≥ 0 (or not finite)
  double pushDistance = 0;     // ε, in world units
  double supportDistance = 0;  // 1.5 grid-cell diagonals, in world units
  DegenerateFieldReport degenerate;
  int defects() const { return spurious + signFailures; }
};

// Contours `field` over `box` and checks it against `samples` (N ≥ 1). Regions where the field
// has no data (ImplicitField::valid) make no contour, so they add no component. Throws as
// marchingSquares / marchingCubes (a non-finite f on the grid is a NumericalError).
template <int Dim>
ZeroSetCheck checkZeroSet(const ImplicitField<Dim>& field, const Box<Dim>& box, const HermiteSamples<Dim>& samples,
                          const ZeroSetCheckOptions& options = {});

}  // namespace hermite
