#pragma once
// The degenerate-field check of a fitted scene (docs/maths.md, "Degenerate fields"): run over the
// region that is meshed and drawn (viewBounds), it records its verdict in the fit's report and,
// for a degenerate field, adds the warning (cause and remedy) and marks the flat regions as
// "no data" (FlatMaskedField), so that views and `mesh` never show them as surface.

#include "scene/scene_fit.h"

namespace hermite {

// Whether the check runs for fits with this kernel: only for the decaying, strictly definite ones
// (gaussian, wendland, inverse-multiquadric). Kernels that grow with distance (multiquadric,
// cubic, polyharmonic) give fields that are not flat away from the data, which is all the check
// looks for, and skipping it saves a whole `fit` process about 30 ms at 1 000 samples.
bool degenerateCheckApplies(KernelType kernel);

// Leaves fit.degenerateField empty where the check does not apply.
template <int Dim>
void checkDegenerateField(const Scene& scene, SceneFit<Dim>& fit);

}  // namespace hermite
