#include "scene/scene_fit_memory.h"

#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/hrbf.h"

namespace hermite {

namespace {

bool implicitMode(const Scene& scene) {
  return scene.mode == SceneMode::Implicit2d || scene.mode == SceneMode::Implicit3d;
}

std::int64_t polynomialTerms(const Scene& scene) {
  return scene.dimension() == 2 ? monomialCount<2>(scene.fit.polynomial) : monomialCount<3>(scene.fit.polynomial);
}

PlannedAllocation densePlan(const Scene& scene, std::int64_t samples) {
  const FitSpec& f = scene.fit;
  const std::int64_t m = polynomialTerms(scene);
  const Kernel kernel{f.kernel, f.radius};
  const SolverChoice path = plannedSolverPath(f.solver, m, kernelDefiniteSign(kernel, f.polynomial, f.smoothing));
  return denseFitPlan(sceneDenseUnknowns(scene, samples), path, m);
}

}  // namespace

std::int64_t sceneDenseUnknowns(const Scene& scene, std::int64_t samples) {
  const std::int64_t perSample = scene.fit.method == FitMethod::Hrbf ? scene.dimension() + 1 : 3;
  return samples * perSample + polynomialTerms(scene);
}

PartitionChoice choosePartition(const Scene& scene, std::int64_t samples, const AvailableMemory& available) {
  const PartitionSwitch s = scene.fit.partition.enabled;
  if (s != PartitionSwitch::Auto || scene.fit.method != FitMethod::Hrbf) return {s == PartitionSwitch::On, {}};
  const std::int64_t n = sceneDenseUnknowns(scene, samples);
  const std::string head = "fit.partition.enabled \"auto\": " + std::to_string(samples) + " samples make a global fit of " +
                           std::to_string(n) + " unknowns, ";
  if (n > kAutoDenseUnknowns)
    return {true, head + "more than " + std::to_string(kAutoDenseUnknowns) + ": fitted by partition of unity"};
  const PlannedAllocation plan = densePlan(scene, samples);
  if (available.bytes != kUnlimitedBytes && plan.bytes >= available.bytes / 2)
    return {true, head + "which need " + formatBytes(plan.bytes) + ", not under half of the " +
                      formatBytes(available.bytes) + " available (" + available.limitedBy +
                      "): fitted by partition of unity"};
  return {false, {}};
}

PartitionChoice choosePartition(const Scene& scene, std::int64_t samples) {
  // The memory is read only where it can decide (a drag refit asks on every step).
  const bool decided = scene.fit.partition.enabled != PartitionSwitch::Auto || scene.fit.method != FitMethod::Hrbf ||
                       sceneDenseUnknowns(scene, samples) > kAutoDenseUnknowns ||
                       densePlan(scene, samples).bytes < kUncheckedBytes;
  return choosePartition(scene, samples, decided ? AvailableMemory{} : availableMemory());
}

std::optional<PlannedAllocation> sceneFitPlan(const Scene& scene, std::int64_t samples) {
  if (!implicitMode(scene) || choosePartition(scene, samples).pu) return std::nullopt;
  return densePlan(scene, samples);
}

}  // namespace hermite
