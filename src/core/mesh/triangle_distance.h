#pragma once
// Euclidean distance from a point to a triangle (its closed face, edges and corners included).

#include "core/base/geometry.h"

namespace hermite {

// Distance from p to triangle (a, b, c); a degenerate triangle measures to its edges.
double pointTriangleDistance(const Vec<3>& p, const Vec<3>& a, const Vec<3>& b, const Vec<3>& c);

}  // namespace hermite
