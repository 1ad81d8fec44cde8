#pragma once
// The ground plane of the 3D view (`view.ground: "grid"`, docs/scene-format.md): a square grid
// of lines on the plane under the data, perpendicular to the camera's up direction, so that the
// eye reads height and orientation while orbiting. Drawn with the overlays, depth-tested against
// the traced surface, which hides the part of the grid behind it.

#include <utility>
#include <vector>

#include "core/base/geometry.h"

namespace hermite::render {

struct GroundGrid {
  std::vector<std::pair<Vec<3>, Vec<3>>> segments;  // the grid's lines, world units
  double spacing = 0;                               // between neighbouring lines, world units
};

// The grid under `points` (3×N; the bounds' corners when empty): on the plane {x : up·x = h} with
// h the lowest up·p, centred under the points' middle, spanning 1.5× their widest extent across
// `up`, with lines 1, 2 or 5 × 10ᵏ apart (about 10 per side). `up` need not be unit; a zero or
// non-finite `up` gives no grid.
GroundGrid groundGrid(const Points<3>& points, const Box<3>& bounds, const Vec<3>& up);

}  // namespace hermite::render
