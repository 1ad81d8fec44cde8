#pragma once
// Scene-file triples (std::array<double, 3>: camera eye, slice normal, ...) as vectors and back.

#include <array>

#include "core/base/geometry.h"

namespace hermite::app {

inline Vec<3> toVec(const std::array<double, 3>& a) { return Vec<3>(a[0], a[1], a[2]); }
inline std::array<double, 3> toArray(const Vec<3>& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace hermite::app
