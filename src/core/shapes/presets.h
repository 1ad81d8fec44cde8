#pragma once
// Built-in data sets, generated exactly (points and exact unit normals). Centred at the origin
// and scaled so the samples fit the unit ball / disc (docs/scene-format.md), unless said otherwise.

#include <string>
#include <string_view>
#include <vector>

#include "core/points/hermite_samples.h"

namespace hermite {

struct PresetInfo {
  std::string name;
  int dimension;                   // 2 or 3
  int defaultCount;                // the preset's own count (count 0 in a scene)
  std::vector<int> suggestedCounts;  // the counts the teaching scenes use
  std::string description;
  int minCount;                    // valid counts: 0 or [minCount, maxCount]
  int maxCount;
};

const std::vector<PresetInfo>& allPresets();
// Throws InputError naming the valid presets for that dimension.
const PresetInfo& presetInfo(std::string_view name);

// count 0 = the preset's own count. Throws InputError for an unknown name, a preset of the
// other dimension, or a count out of range (the message says the valid range).
HermiteSamples<2> makePreset2d(std::string_view name, int count);
HermiteSamples<3> makePreset3d(std::string_view name, int count);

// ---- the exact shapes behind the generated presets (for analytic checks) ------------------

// A torus: centre, unit axis, major radius R (centre to tube centre), minor radius r (tube).
struct TorusGeometry {
  Vec<3> centre;
  Vec<3> axis;
  double major;
  double minor;
};
// "torus": one torus about the z axis (R = 0.7, r = 0.3, so R + r = 1).
// "two-tori": two interlinked tori R = 5/9, r = 1/6, centred at (∓5/18, 0, 0) with axes z and y:
// each core circle passes through the other's centre, the tubes are 2/9 apart at their closest,
// the bounding box is centred at the origin and the farthest surface point is at distance 1.
std::vector<TorusGeometry> presetTori(std::string_view name);

// "curve2d" before centring and scaling: the polar curve r(θ) = 1 + 0.35·cos 3θ, θ ∈ [0, 2π),
// counter-clockwise, non-convex (its curvature changes sign), simple (r > 0).
// Preset point = scale · (r(θ)(cos θ, sin θ) − centre): centre = the curve's bounding-box centre,
// scale = 1 / (largest distance of the curve from that centre).
double curve2dRadius(double theta);
struct Curve2dFrame {
  Vec<2> centre;
  double scale;
};
const Curve2dFrame& curve2dFrame();

}  // namespace hermite
