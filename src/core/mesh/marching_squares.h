#pragma once
// Marching squares: the zero set of a 2D field as polylines (marching_options.h explains the method).

#include <vector>

#include "core/base/geometry.h"
#include "core/base/implicit_field.h"
#include "core/mesh/marching_options.h"

namespace hermite {

// One contour line, points in order. closed: the last point connects to the first (else the
// curve leaves the box at both ends).
struct Polyline2d {
  Points<2> points;  // 2 × n
  bool closed = false;
};

// Marching squares. Throws InputError for an empty box or a resolution < 1, NumericalError when
// f is not finite at a grid point (naming the point).
std::vector<Polyline2d> marchingSquares(const ImplicitField<2>& field, const Box<2>& box,
                                        const MarchingOptions& options = {}, MarchingReport* report = nullptr);

}  // namespace hermite
