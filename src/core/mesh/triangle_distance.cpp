// Point-to-triangle distance (triangle_distance.h): the foot of the perpendicular when it falls
// inside the face, else the nearest of the three edges.

#include "core/mesh/triangle_distance.h"

#include <algorithm>

namespace hermite {

namespace {

double pointSegmentDistance(const Vec<3>& p, const Vec<3>& a, const Vec<3>& b) {
  const Vec<3> ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

double pointTriangleDistance(const Vec<3>& p, const Vec<3>& a, const Vec<3>& b, const Vec<3>& c) {
  const Vec<3> n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Vec<3> foot = p - ((p - a).dot(n) / n2) * n;
    // The foot is inside when it lies on the inner side of all three edges.
    const bool inside = (b - a).cross(foot - a).dot(n) >= 0 && (c - b).cross(foot - b).dot(n) >= 0 &&
                        (a - c).cross(foot - c).dot(n) >= 0;
    if (inside) return (p - foot).norm();
  }
  return std::min({pointSegmentDistance(p, a, b), pointSegmentDistance(p, b, c), pointSegmentDistance(p, c, a)});
}

}  // namespace hermite
