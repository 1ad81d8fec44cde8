#pragma once
// k-fold validation of a scene's fit (docs/maths.md, "Suggesting r"): for fits without a closed-form
// leave-one-out — partition of unity and RBF-offset — sample i goes to fold i mod k; each fold is
// held out in turn, the scene refitted on the other samples and evaluated at the held-out ones.
// The summary has the leave-one-out's terms, so the two rank radii alike.

#include "core/rbf/leave_one_out.h"
#include "scene/scene_file.h"

namespace hermite {

inline constexpr int kHoldoutFolds = 5;

// The scene's fit validated on `folds` folds (2 ≤ folds ≤ N; InputError otherwise). The refits
// use the scene's fit settings on inline data, without its `transform` (errors are measured in
// the frame of the samples). Throws what fitScene throws (a fold that cannot be fitted).
template <int Dim>
LeaveOneOutResult kFoldValidation(const Scene& scene, const HermiteSamples<Dim>& samples, int folds = kHoldoutFolds);

}  // namespace hermite
