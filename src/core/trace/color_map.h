#pragma once
// The diverging colour map of the 2D field view and the slice plane (docs/maths.md, Colour map): symmetric
// about f = 0 (blue inside, f < 0; near-white at 0; orange-red outside, f > 0: the colour at −t
// is the colour at t with red and blue swapped), and the zero-curve
// colour, which is not a colour of the map. The stops are public so shaders get the same numbers.

#include <array>

#include "core/base/geometry.h"

namespace hermite {

struct ColorStop {
  double t;  // position in [−1, 1]: f / range
  double r, g, b;
};

// Stop k and stop 4 − k have opposite t and swapped red / blue channels.
inline constexpr std::array<ColorStop, 5> kDivergingStops{{
    {-1.0, 0.085, 0.250, 0.600},
    {-0.5, 0.420, 0.620, 0.860},
    {0.0, 0.965, 0.965, 0.965},
    {0.5, 0.860, 0.620, 0.420},
    {1.0, 0.600, 0.250, 0.085},
}};

// Zero curve: pure black. Every map colour has a channel ≥ 0.6, so black is ≥ 0.6 away from it.
inline constexpr std::array<double, 3> kZeroCurveColor{0.0, 0.0, 0.0};
// No data (ImplicitField::valid false): light grey with diagonal hatching, neither a map colour
// nor a line. A pixel in GL column i, row r (r = 0 at the bottom) is hatched when
// (i + r) mod kNoDataHatchPeriod < kNoDataHatchWidth. Neither iso-lines nor the zero curve are
// drawn there.
inline constexpr std::array<double, 3> kNoDataColor{0.80, 0.80, 0.80};
inline constexpr std::array<double, 3> kNoDataHatchColor{0.62, 0.62, 0.62};
inline constexpr int kNoDataHatchPeriod = 8;
inline constexpr int kNoDataHatchWidth = 2;
// Iso-lines: the map colour scaled by this factor (darker, still of the map's hue).
inline constexpr double kIsoLineDarken = 0.72;

// Colour of f at range > 0 (values beyond ±range clamp to the end stops); NaN gives mid grey.
Vec<3> divergingColor(double f, double range);
// Colour at the normalised position t ∈ [−1, 1] (piecewise linear between the stops).
Vec<3> divergingColorAt(double t);

// A "nice" iso-line spacing (1, 2 or 5 × 10ᵏ) giving about `lines` lines on each side of 0.
double niceIsoSpacing(double range, int lines = 5);

}  // namespace hermite
