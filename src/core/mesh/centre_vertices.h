#pragma once
// Centre vertices of marching cubes' polygons (docs/maths.md, Contouring).
//
// A contour polygon of one cube that no fan can triangulate without a diagonal on a cube face
// gets a fan around an extra vertex. It starts at the mean of the polygon's edge vertices, which
// lies off f = 0 wherever the polygon is far from flat: the 12-gon a part thinner than a cell
// leaves in its cube (a horn of the Stanford dragon at 200 000 samples, 256³) had its mean on
// the horn's axis, a sample spacing from the surface, |f| 4·10⁻⁴ where every edge vertex had
// 10⁻⁶. Each centre moves to the root of f nearest the mean on five lines through it: its
// polygon's area normal (on which the fan stays a fan), ∇f there and the three axes (a thin
// part running along the area normal has its surface across it), each kept inside the box of the
// polygon's vertices (so inside its cube, whose edges hold those vertices). A centre with no
// sign change on any of them keeps the mean and is counted.

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"

namespace hermite {

struct CentreVertexReport {
  int centres = 0;     // centre vertices placed
  int offZeroSet = 0;  // of those, left at their polygon's mean: no root of f on their lines
  double maxAbsF = 0;  // max |f| over the centres on f = 0 (those left at the mean excluded)
};

// Moves the columns of X (3 × C: the polygons' mean vertices) onto f = 0 (above), with `axis`
// (3 × C) the polygons' area normals (any length) and [lo, hi] (3 × C) the boxes of their
// vertices. G receives ∇f at the final positions.
CentreVertexReport placeCentreVertices(const ImplicitField<3>& field, Points<3>& X, const Points<3>& axis,
                                       const Points<3>& lo, const Points<3>& hi, Points<3>& G,
                                       const CancelToken* cancel = nullptr);

}  // namespace hermite
