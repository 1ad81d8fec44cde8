#pragma once
// The data reach of a global fit of a data file (docs/maths.md, "No data"; docs/scene-format.md,
// fit.partition.data_reach): a scanned cloud is often open (a bust's base, a half sphere), and
// the global interpolant's zero set goes on past its last samples to view.bounds. The partition
// of unity marks points beyond c·dₖ of every sample as "no data"; a global fit of a file's
// samples gets the same reach (ReachMaskedField), so that the mesh export, the tracers and the
// 2D view end the surface near the data whichever fit the size chose. Preset, inline and
// hand-made data (fewer than kReachMinSamples samples) keep the whole zero set: what they teach
// is the interpolant itself.

#include "scene/scene_fit.h"

namespace hermite {

// A data file with fewer samples is hand-made (as for the orientation of its normals): its zero
// set is meant whole.
inline constexpr int kReachMinSamples = 50;

// Whether fit.reach_mask "auto" masks data like `data` with `samples` samples: a file of at least
// kReachMinSamples.
bool reachMaskAuto(const DataSpec& data, int samples);

// Wraps fit.field() in the samples' data reach (fit.masked, owning what it held) for a global fit
// whose fit.reach_mask is true, or "auto" and reachMaskAuto; leaves other fits as they are.
template <int Dim>
void maskBeyondDataReach(const Scene& scene, SceneFit<Dim>& fit);

// Whether maskBeyondDataReach masks this fit.
template <int Dim>
bool dataReachApplies(const Scene& scene, const SceneFit<Dim>& fit);

}  // namespace hermite
