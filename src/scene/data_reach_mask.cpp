#include "scene/data_reach_mask.h"

#include "core/pu/reach_masked_field.h"

namespace hermite {

bool reachMaskAuto(const DataSpec& data, int samples) { return !data.file.empty() && samples >= kReachMinSamples; }

template <int Dim>
bool dataReachApplies(const Scene& scene, const SceneFit<Dim>& fit) {
  if (fit.pu() != nullptr || fit.data.size() == 0 || scene.fit.reachMask == AutoSwitch::Off) return false;
  return scene.fit.reachMask == AutoSwitch::On || reachMaskAuto(scene.data, fit.data.size());
}

template <int Dim>
void maskBeyondDataReach(const Scene& scene, SceneFit<Dim>& fit) {
  if (!dataReachApplies<Dim>(scene, fit)) return;
  const ImplicitField<Dim>& inner = fit.field();
  fit.masked = std::make_unique<ReachMaskedField<Dim>>(inner, fit.data.points, scene.fit.partition.dataReach,
                                                       PuOptions{}.vertexReach, std::move(fit.masked));
}

template bool dataReachApplies<2>(const Scene&, const SceneFit<2>&);
template bool dataReachApplies<3>(const Scene&, const SceneFit<3>&);
template void maskBeyondDataReach<2>(const Scene&, SceneFit<2>&);
template void maskBeyondDataReach<3>(const Scene&, SceneFit<3>&);

}  // namespace hermite
