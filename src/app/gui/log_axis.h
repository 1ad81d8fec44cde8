#pragma once
// A logarithmic axis for the r explorer's plots (and any plot against r): the map between a value
// in [lo, hi] and a pixel in [x0, x1] — linear in log10 — and its ticks: one per decade with a
// label ("0.01", "0.1", "1", "10", "1e+03"), or, when the range spans less than one decade, the
// 1-2-5 multiples inside it, so that a plot always has at least two labelled ticks.

#include <string>
#include <vector>

namespace hermite::app {

struct AxisTick {
  double value = 0;
  double pixel = 0;
  std::string label;
};

class LogAxis {
 public:
  // 0 < lo, lo ≤ hi (equal bounds are widened by a factor √10 either side); pixels x0 < x1.
  LogAxis(double lo, double hi, double x0, double x1);

  double toPixel(double value) const;    // values ≤ 0 map to x0
  double fromPixel(double pixel) const;  // clamped to [x0, x1] first
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  std::vector<AxisTick> ticks() const;

 private:
  double lo_, hi_, x0_, x1_;
};

// The label of a tick value: "%g" with at most 3 significant digits.
std::string tickLabel(double value);

}  // namespace hermite::app
