#pragma once
// The region that is baked, traced, sliced and meshed (DESIGN.md §4 `view.bounds`).

#include "core/geometry.h"
#include "core/scene_file.h"

namespace hermite {

// The samples' bounding box grown on every side by 25 % of its largest extent. When every
// extent is 0 (one point, or all points equal) the margin is 1. Samples: Dim × N, N ≥ 1
// (InputError otherwise, and for non-finite points).
template <int Dim>
Box<Dim> defaultViewBounds(const Points<Dim>& samples);

// `view.bounds` when given (2·Dim numbers: min then max; InputError naming the key when the
// count is wrong, a value is not finite or min ≥ max), else defaultViewBounds(samples).
template <int Dim>
Box<Dim> viewBounds(const ViewSpec& view, const Points<Dim>& samples);

}  // namespace hermite
