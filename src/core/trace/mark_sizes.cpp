#include "core/trace/mark_sizes.h"

#include <algorithm>

#include "core/points/hermite_samples.h"

namespace hermite {

MarkSizes markSizes2d(const Field2dStyle& style, const View2d& view, const Points<2>& points) {
  MarkSizes m{style.normalLengthPx, style.pointRadiusPx};
  if (points.cols() < 2) return m;
  const double pxPerUnit = (view.worldToPixel(Vec<2>(1, 0)) - view.worldToPixel(Vec<2>(0, 0))).norm();
  const double spacingPx = meanSampleSpacing<2>(points) * pxPerUnit;
  if (!(spacingPx > 0)) return m;
  m.normalLengthPx = std::min(m.normalLengthPx, 2.0 * spacingPx);
  m.pointRadiusPx = spacingPx < kMinDotGapPx ? 0.0
                                             : std::clamp(0.25 * spacingPx, std::min(1.5, m.pointRadiusPx), m.pointRadiusPx);
  return m;
}

}  // namespace hermite
