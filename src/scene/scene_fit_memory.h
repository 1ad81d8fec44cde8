#pragma once
// The memory of a scene's global fit before it starts (core/rbf/dense_fit_memory.h): what
// `sweep` checks once for all radii, and what chooses between a dense and a partition-of-unity
// fit by size.

#include <cstdint>
#include <optional>

#include "core/base/memory_check.h"
#include "scene/scene_file.h"

namespace hermite {

// The dense fit of `samples` samples with the scene's fit settings: HRBF (Dim + 1)·N + m
// unknowns, RBF-offset 3·N + m, on the solver path the settings choose. nullopt for a
// partition-of-unity fit (fitPu sizes its local fits itself) and for modes without a fit.
std::optional<PlannedAllocation> sceneFitPlan(const Scene& scene, std::int64_t samples);

}  // namespace hermite
