#pragma once
// The degenerate-field check of a fitted scene (docs/maths.md, "Degenerate fields"): run over the
// region that is meshed and drawn (viewBounds), it records its verdict in the fit's report and,
// for a degenerate field, adds the warning (cause and remedy) and marks the flat regions as
// "no data" (FlatMaskedField), so that views and `mesh` never show them as surface.

#include "scene/scene_fit.h"

namespace hermite {

template <int Dim>
void checkDegenerateField(const Scene& scene, SceneFit<Dim>& fit);

}  // namespace hermite
