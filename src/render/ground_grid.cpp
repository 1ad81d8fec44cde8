#include "render/ground_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace hermite::render {

namespace {

// The 1, 2, 5 × 10ᵏ at or above `x` > 0: grid spacings that read as round numbers.
double niceStep(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= x * (1 - 1e-12)) return m * decade;
  return 10 * decade;
}

}  // namespace

GroundGrid groundGrid(const Points<3>& points, const Box<3>& bounds, const Vec<3>& up) {
  GroundGrid grid;
  const double upNorm = up.norm();
  if (!(upNorm > 0) || !std::isfinite(upNorm)) return grid;
  const Vec<3> n = up / upNorm;
  // Two unit directions across `up`.
  const Vec<3> helper = std::abs(n.x()) < 0.9 ? Vec<3>(1, 0, 0) : Vec<3>(0, 1, 0);
  const Vec<3> u = n.cross(helper).normalized(), v = n.cross(u);
  Points<3> P = points;
  if (P.cols() == 0) {
    P.resize(3, 8);
    for (int c = 0; c < 8; ++c)
      P.col(c) = Vec<3>((c & 1) ? bounds.hi.x() : bounds.lo.x(), (c & 2) ? bounds.hi.y() : bounds.lo.y(),
                        (c & 4) ? bounds.hi.z() : bounds.lo.z());
  }
  double h = std::numeric_limits<double>::infinity();
  double ulo = h, uhi = -h, vlo = h, vhi = -h;
  for (Eigen::Index k = 0; k < P.cols(); ++k) {
    const Vec<3> p = P.col(k);
    h = std::min(h, n.dot(p));
    ulo = std::min(ulo, u.dot(p)), uhi = std::max(uhi, u.dot(p));
    vlo = std::min(vlo, v.dot(p)), vhi = std::max(vhi, v.dot(p));
  }
  const double extent = std::max(uhi - ulo, vhi - vlo);
  if (!(extent > 0) || !std::isfinite(extent) || !std::isfinite(h)) return grid;
  grid.spacing = niceStep(1.5 * extent / 10);
  const int half = int(std::ceil(0.75 * extent / grid.spacing));
  // Lines through multiples of the spacing (a grid that stays put as the data move a little).
  const double uc = std::round(0.5 * (ulo + uhi) / grid.spacing) * grid.spacing;
  const double vc = std::round(0.5 * (vlo + vhi) / grid.spacing) * grid.spacing;
  const double reach = half * grid.spacing;
  const auto at = [&](double a, double b) { return Vec<3>(h * n + a * u + b * v); };
  for (int k = -half; k <= half; ++k) {
    const double a = k * grid.spacing;
    grid.segments.emplace_back(at(uc + a, vc - reach), at(uc + a, vc + reach));
    grid.segments.emplace_back(at(uc - reach, vc + a), at(uc + reach, vc + a));
  }
  return grid;
}

}  // namespace hermite::render
