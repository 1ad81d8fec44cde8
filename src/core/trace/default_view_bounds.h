#pragma once
// The region baked, traced, sliced and meshed when the scene gives no `view.bounds`.

#include "core/base/geometry.h"

namespace hermite {

// The samples' bounding box grown on every side by 25 % of its largest extent. When every
// extent is 0 (one point, or all points equal) the margin is 1. Samples: Dim × N, N ≥ 1
// (InputError otherwise, and for non-finite points).
template <int Dim>
Box<Dim> defaultViewBounds(const Points<Dim>& samples);

}  // namespace hermite
