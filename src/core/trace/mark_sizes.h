#pragma once
// Sizes of the sample marks of a 2D view scaled to the mean sample spacing s (in pixels), so that
// a dense cloud is not a hairball of normals over a carpet of dots: normals at most 2·s long,
// dots at most s/2 wide (radius ≥ 1.5 px), and none while s is under kMinDotGapPx (they would
// cover the field); sparse clouds keep the style's sizes. The GPU view and the CPU reference use
// the same sizes; the 3D view has the same rule (implicit_tracer.cpp).

#include "core/trace/field2d_reference.h"

namespace hermite {

inline constexpr double kMinDotGapPx = 2.0;

struct MarkSizes {
  double normalLengthPx = 0;
  double pointRadiusPx = 0;  // 0: no dots
};

// points: 2 × N in world units, drawn through `view`.
MarkSizes markSizes2d(const Field2dStyle& style, const View2d& view, const Points<2>& points);

}  // namespace hermite
