#include "core/trace/color_map.h"

#include <algorithm>
#include <cmath>

namespace hermite {

Vec<3> divergingColorAt(double t) {
  if (std::isnan(t)) return Vec<3>(0.5, 0.5, 0.5);
  t = std::clamp(t, -1.0, 1.0);
  for (std::size_t k = 0; k + 1 < kDivergingStops.size(); ++k) {
    const ColorStop& a = kDivergingStops[k];
    const ColorStop& b = kDivergingStops[k + 1];
    if (t <= b.t) {
      const double s = (t - a.t) / (b.t - a.t);
      return Vec<3>(a.r + s * (b.r - a.r), a.g + s * (b.g - a.g), a.b + s * (b.b - a.b));
    }
  }
  const ColorStop& e = kDivergingStops.back();
  return Vec<3>(e.r, e.g, e.b);
}

Vec<3> divergingColor(double f, double range) { return divergingColorAt(f / range); }

double niceIsoSpacing(double range, int lines) {
  if (!(range > 0) || !std::isfinite(range) || lines < 1) return 1.0;
  const double raw = range / lines;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  const double nice = m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0;
  return nice * p;
}

}  // namespace hermite
