#pragma once
// Leave-one-out error of an HRBF fit by the closed form (a block version of Rippa's formula):
// for the saddle system M z = y (M = [A P; Pᵀ 0]) and the rows S of sample i (its value and
// gradient conditions, which are also the columns of its centre's α, β), the fit without
// sample i predicts at pᵢ
//     y_S − pred_S = ((M⁻¹)_SS)⁻¹ z_S,
// because (M⁻¹)_SS is the inverse of the Schur complement of the reduced system. One inverse
// of M (O(n³)) replaces N refits (O(N·n³)). Exact for any λ: the smoothing term sits on the
// diagonal of S's own block, which the reduced model does not contain.

#include <string>
#include <vector>

#include "core/rbf/hrbf.h"

namespace hermite {

struct LeaveOneOutResult {
  std::vector<double> valueError;     // per sample: |f₋ᵢ(pᵢ)|
  std::vector<double> gradientError;  // per sample: ‖∇f₋ᵢ(pᵢ) − nᵢ‖
  double rmsValue = 0;                // root mean square of valueError
  double rmsGradient = 0;             // root mean square of gradientError
  double maxValue = 0;
  double maxGradient = 0;
  // One number for plots and the suggested r: √(rmsValue² + (h·rmsGradient)²), with h the mean
  // nearest-neighbour spacing, so that both errors are lengths.
  double combined = 0;
};

// Throws NumericalError (with the reason) when M or one of its diagonal blocks is singular, and
// InputError for fewer than two samples.
template <int Dim>
LeaveOneOutResult hrbfLeaveOneOut(const HermiteSamples<Dim>& samples, const HrbfOptions& options);

// The brute-force definition (N refits), for tests on small data.
template <int Dim>
LeaveOneOutResult hrbfLeaveOneOutBruteForce(const HermiteSamples<Dim>& samples, const HrbfOptions& options);

}  // namespace hermite
