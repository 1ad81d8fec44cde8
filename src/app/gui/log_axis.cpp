#include "app/gui/log_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hermite::app {

LogAxis::LogAxis(double lo, double hi, double x0, double x1) : lo_(lo), hi_(hi), x0_(x0), x1_(x1) {
  if (!(lo_ > 0)) lo_ = 1e-300;
  if (!(hi_ >= lo_)) hi_ = lo_;
  if (hi_ == lo_) {
    lo_ /= std::sqrt(10.0);
    hi_ *= std::sqrt(10.0);
  }
}

double LogAxis::toPixel(double value) const {
  if (!(value > 0)) return x0_;
  const double t = (std::log10(value) - std::log10(lo_)) / (std::log10(hi_) - std::log10(lo_));
  return x0_ + t * (x1_ - x0_);
}

double LogAxis::fromPixel(double pixel) const {
  const double t = (std::clamp(pixel, x0_, x1_) - x0_) / (x1_ - x0_);
  return std::pow(10.0, std::log10(lo_) + t * (std::log10(hi_) - std::log10(lo_)));
}

std::vector<AxisTick> LogAxis::ticks() const {
  std::vector<AxisTick> out;
  const int d0 = int(std::floor(std::log10(lo_))), d1 = int(std::ceil(std::log10(hi_)));
  // Decades first; with fewer than two inside the range, the 1-2-5 multiples.
  for (int pass = 0; pass < 2 && out.size() < 2; ++pass) {
    out.clear();
    for (int d = d0; d <= d1; ++d)
      for (double m : pass == 0 ? std::vector<double>{1} : std::vector<double>{1, 2, 5}) {
        const double v = m * std::pow(10.0, d);
        if (v >= lo_ * (1 - 1e-12) && v <= hi_ * (1 + 1e-12)) out.push_back({v, toPixel(v), tickLabel(v)});
      }
  }
  return out;
}

std::string tickLabel(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", value);
  return buf;
}

}  // namespace hermite::app
