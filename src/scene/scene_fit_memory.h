#pragma once
// The memory of a scene's global fit before it starts (core/rbf/dense_fit_memory.h): what
// `sweep` checks once for all radii, and what chooses between a dense and a partition-of-unity
// fit by size (fit.partition.enabled "auto").

#include <cstdint>
#include <optional>
#include <string>

#include "core/base/memory_check.h"
#include "scene/scene_file.h"

namespace hermite {

// "auto" fits densely up to this many unknowns (a dense HRBF fit of 10 000 unknowns takes a few
// seconds and 0.8–2.4 GB; docs/performance.md), by partition of unity above.
inline constexpr std::int64_t kAutoDenseUnknowns = 10000;

// Unknowns of the dense fit of `samples` samples with the scene's fit settings: HRBF
// (Dim + 1)·N + m, RBF-offset 3·N + m.
std::int64_t sceneDenseUnknowns(const Scene& scene, std::int64_t samples);

// Which fit a scene of `samples` samples runs (implicit modes). fit.partition.enabled true →
// partition of unity, false → dense; "auto" → dense when its unknowns are at most
// kAutoDenseUnknowns and its planned memory (denseFitPlan) is under half of `available`, else
// partition of unity with `message` saying why. RBF-offset has no partition of unity: dense.
struct PartitionChoice {
  bool pu = false;
  std::string message;  // set when "auto" chose partition of unity
};
PartitionChoice choosePartition(const Scene& scene, std::int64_t samples, const AvailableMemory& available);
// The same against availableMemory().
PartitionChoice choosePartition(const Scene& scene, std::int64_t samples);

// The dense fit of `samples` samples with the scene's fit settings, on the solver path the
// settings choose. nullopt when choosePartition picks partition of unity (fitPu sizes its local
// fits itself) and for modes without a fit.
std::optional<PlannedAllocation> sceneFitPlan(const Scene& scene, std::int64_t samples);

}  // namespace hermite
