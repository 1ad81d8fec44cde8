#pragma once
// The colours the rasterised views give a meaning to, in one place for the renderer
// (scene_view.cpp) and the legends that explain them (view_legends.h). Linear RGB in [0, 1].

#include <array>

namespace hermite::app {

inline constexpr std::array<double, 3> kPatchErrorColour{0.9, 0.12, 0.08};  // the largest patch error
inline constexpr std::array<double, 3> kHolePatchColour{0.25, 0.7, 0.7};    // triangles a hole fill added
inline constexpr std::array<double, 3> kHoleRimColour{0.9, 0.1, 0.1};       // hole boundaries
inline constexpr std::array<double, 3> kRingNormalColour{0.1, 0.55, 0.15};  // ring samples given to the implicit

}  // namespace hermite::app
