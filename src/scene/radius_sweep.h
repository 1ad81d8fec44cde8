#pragma once
// The r-sensitivity sweep (the GUI's "Explore r" panel and `hermite-lab sweep`): the scene's data and fit
// settings refitted at k radii spaced logarithmically between two bounds, with the diagnostics
// a user compares across r — condition estimate, residuals, leave-one-out error — and the
// radius with the smallest leave-one-out error as the suggestion.

#include <atomic>
#include <string>
#include <vector>

#include "scene/scene_file.h"

namespace hermite {

struct RadiusSweepRow {
  double radius = 0;
  double radiusInSpacing = 0;        // r / mean nearest-neighbour spacing of the samples
  std::string solver;
  double conditionEstimate = 0;
  double maxAbsF = 0;                // max |f(pᵢ)| of the fit at this r
  double maxGradError = 0;           // max ‖∇f(pᵢ) − nᵢ‖
  double looRmsValue = NAN;          // leave-one-out (HRBF fits; NaN for RBF-offset)
  double looRmsGradient = NAN;
  double looCombined = NAN;          // LeaveOneOutResult::combined
  double fitMs = 0;
  std::string looError;              // non-empty: the fit is fine but M is numerically singular
  std::string error;                 // non-empty: this radius failed to fit (the reason)
  bool ok() const { return error.empty(); }
};

// k radii a·(b/a)^(i/(k−1)), i = 0..k−1 (k = 1: a). InputError unless 0 < a ≤ b, k in [1, 1000].
std::vector<double> logSpacedRadii(double a, double b, int k);

// "A:B:K" (the --radii argument) → logSpacedRadii(A, B, K); UsageError when malformed.
std::vector<double> parseRadiiArgument(const std::string& text);

// Fits the scene at each radius (the scene's own radius ignored). A fit that fails becomes a
// row with `error` set, not an exception. `cancel` (may be null) stops between radii; the rows
// done so far are returned. `progress` (may be null) is set to the fraction done.
template <int Dim>
std::vector<RadiusSweepRow> sweepRadii(const Scene& scene, const std::vector<double>& radii,
                                       const std::atomic<bool>* cancel = nullptr, std::atomic<float>* progress = nullptr);

// The diagnostics row of one fitted scene (`scene` as fitted, its radius being the row's r);
// `spacing` is the samples' mean nearest-neighbour distance.
template <int Dim>
struct SceneFit;
template <int Dim>
RadiusSweepRow radiusSweepRow(const Scene& scene, const SceneFit<Dim>& fit, double spacing);

// Index of the row with the smallest finite looCombined (−1 when none).
int suggestedRadiusIndex(const std::vector<RadiusSweepRow>& rows);

// The rows as CSV with a header line (what `sweep` writes as diagnostics.csv and the GUI exports);
// with `images` (one per row) a last column `image` names each row's picture.
std::string radiusSweepCsv(const std::vector<RadiusSweepRow>& rows, const std::vector<std::string>* images = nullptr);

}  // namespace hermite
