#pragma once
// The r-sensitivity sweep (the GUI's "Explore r" panel and `hermite-lab sweep`): the scene's data and fit
// settings refitted at k radii spaced logarithmically between two bounds, with the diagnostics
// a user compares across r — condition estimate, residuals, leave-one-out error, the zero set's
// components — and a suggested radius (docs/maths.md, "Suggesting r"): among the radii whose
// condition estimate is at most 10¹⁴ and whose validation error is finite, fields that are not
// degenerate come first, then the fewest spurious components and sign failures, then the least
// validation error.

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
  // What the suggestion ranks by: "leave-one-out" (global HRBF, closed form) or "5-fold"
  // (partition of unity, RBF-offset: kFoldValidation); validationError is its combined error.
  std::string validation;
  double validationError = NAN;
  int components = -1;               // curves (2D) / surfaces (3D) of the zero set in the view; −1: not checked
  int spuriousComponents = -1;       // of which near no sample
  int signFailures = -1;             // samples whose ±εn pushed points have the wrong sign
  double flatFraction = NAN;         // of the view where f is flat (degenerate_field.h)
  bool degenerate = false;           // flatFraction above DegenerateFieldOptions::largeFraction
  std::string zeroSetError;          // non-empty: the zero set could not be contoured (why)
  std::string looError;              // non-empty: the fit is fine but M is numerically singular
  std::string error;                 // non-empty: this radius failed to fit (the reason)
  bool ok() const { return error.empty(); }
  // Why the suggestion skips this row ("" when it is a candidate): "failed", "ill-conditioned"
  // (condition estimate above kSuggestionMaxCondition), "validation not finite".
  std::string rejection() const;
  int defects() const { return spuriousComponents < 0 ? 0 : spuriousComponents + signFailures; }
};

// Above this condition estimate a radius is never suggested: about 2 of double's 16 digits are left.
inline constexpr double kSuggestionMaxCondition = 1e14;

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

// Index of the suggested row (−1 when no row is a candidate): among rows with an empty
// rejection(): not degenerate first, then the fewest defects(), then the least validationError.
int suggestedRadiusIndex(const std::vector<RadiusSweepRow>& rows);

// One row's verdict in words, for `sweep`'s standard output and the explorer's tooltips:
// "loo 0.0123  1 curve", "5-fold 0.02  3 surfaces (2 spurious, 4 sign failures)",
// "ill-conditioned" (a rejected row), or "failed: REASON". `dim` picks curves or surfaces.
std::string radiusSweepVerdict(const RadiusSweepRow& row, int dim);

// The rows as CSV with a header line (what `sweep` writes as diagnostics.csv and the GUI exports);
// with `images` (one per row) a last column `image` names each row's picture.
std::string radiusSweepCsv(const std::vector<RadiusSweepRow>& rows, const std::vector<std::string>* images = nullptr);

}  // namespace hermite
