#pragma once
// The region that is baked, traced, sliced and meshed (`view.bounds`, docs/scene-format.md).

#include <string>
#include <vector>

#include "core/base/geometry.h"
#include "core/trace/default_view_bounds.h"
#include "scene/scene_file.h"

namespace hermite {

// Why `bounds` (2·dim numbers: min then max) is not a view box — a wrong count, a value that is not
// finite, or min ≥ max on some axis — or "" when it is one. The scene parser and viewBounds both
// check through it.
std::string viewBoundsProblem(const std::vector<double>& bounds, int dim);

// `view.bounds` when given (2·Dim numbers: min then max; InputError naming the key when the
// count is wrong, a value is not finite or min ≥ max), else defaultViewBounds(samples).
template <int Dim>
Box<Dim> viewBounds(const ViewSpec& view, const Points<Dim>& samples);

}  // namespace hermite
