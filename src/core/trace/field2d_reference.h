#pragma once
// CPU reference rendering of a 2D field (docs/maths.md, Conventions): the heat map of f in the
// diverging colour map, iso-lines at a regular spacing, the zero curve thick and anti-aliased in
// a colour outside the map, optional samples (dots) and normals (short lines). The GPU 2D view
// is tested against it. Line widths use the distance estimate |f − level| / ‖∇f‖ in pixels.

#include <cstdint>
#include <vector>

#include "core/base/implicit_field.h"
#include "core/trace/camera.h"
#include "core/trace/image.h"

namespace hermite {

struct Field2dStyle {
  double range = 0;          // colour map covers [−range, range]; 0 = max |f| over the pixel centres
  double isoSpacing = 0;     // 0 = niceIsoSpacing(range); < 0 = no iso-lines
  double zeroWidthPx = 2.5;  // full width of the zero curve
  double isoWidthPx = 1.0;   // full width of an iso-line
  double pointRadiusPx = 3.0;
  double normalLengthPx = 18.0;
  std::array<double, 3> pointColor{0.1, 0.1, 0.1};
  std::array<double, 3> normalColor{0.15, 0.15, 0.15};
};

struct Field2dImage {
  ImageRgba8 image;              // W × H, row 0 = top (largest y)
  std::vector<float> value;      // W·H, f at the pixel centres
  std::vector<float> zeroCoverage;  // W·H, coverage of the zero curve in [0, 1]
  double range = 0;              // the colour-map range used
  double isoSpacing = 0;         // the iso-line spacing used (≤ 0: none)
  double ms = 0;
};

// points / normals: 2 × N each (may be empty; normals ignored when their count differs).
Field2dImage renderField2dReference(const ImplicitField<2>& field, const View2d& view, const Field2dStyle& style = {},
                                    const Points<2>& points = Points<2>(2, 0),
                                    const Points<2>& normals = Points<2>(2, 0));

}  // namespace hermite
