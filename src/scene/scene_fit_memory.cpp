#include "scene/scene_fit_memory.h"

#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/hrbf.h"

namespace hermite {

std::optional<PlannedAllocation> sceneFitPlan(const Scene& scene, std::int64_t samples) {
  if (scene.mode != SceneMode::Implicit2d && scene.mode != SceneMode::Implicit3d) return std::nullopt;
  const FitSpec& f = scene.fit;
  if (f.partition.enabled) return std::nullopt;
  const int dim = scene.dimension();
  const std::int64_t m = dim == 2 ? monomialCount<2>(f.polynomial) : monomialCount<3>(f.polynomial);
  const std::int64_t perSample = f.method == FitMethod::Hrbf ? dim + 1 : 3;
  const Kernel kernel{f.kernel, f.radius};
  const SolverChoice path = plannedSolverPath(f.solver, m, kernelDefiniteSign(kernel, f.polynomial, f.smoothing));
  return denseFitPlan(samples * perSample + m, path, m);
}

}  // namespace hermite
