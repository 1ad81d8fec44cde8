#pragma once
// Built-in data sets, generated exactly (points and exact unit normals). Centred at the origin
// and scaled so the samples fit the unit ball / disc (DESIGN.md §4), unless said otherwise.

#include <string>
#include <string_view>
#include <vector>

#include "core/hermite_samples.h"

namespace hermite {

struct PresetInfo {
  std::string name;
  int dimension;                   // 2 or 3
  int defaultCount;                // the preset's own count (count 0 in a scene)
  std::vector<int> suggestedCounts;  // the counts the teaching scenes use
  std::string description;
};

const std::vector<PresetInfo>& allPresets();
// Throws InputError naming the valid presets for that dimension.
const PresetInfo& presetInfo(std::string_view name);

// count 0 = the preset's own count. Throws InputError for an unknown name, a preset of the
// other dimension, or a count out of range (the message says the valid range).
HermiteSamples<2> makePreset2d(std::string_view name, int count);
HermiteSamples<3> makePreset3d(std::string_view name, int count);

}  // namespace hermite
