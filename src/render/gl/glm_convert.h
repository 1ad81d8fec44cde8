#pragma once
// Double-precision core types → the float glm types GL uniforms take (one place for the
// conversions every renderer needs).

#include <glm/glm.hpp>

#include <array>

#include "core/base/geometry.h"

namespace hermite::render {

inline glm::vec3 toGlm(const Vec<3>& v) { return glm::vec3(float(v.x()), float(v.y()), float(v.z())); }
inline glm::vec3 toGlm(const std::array<double, 3>& a) { return glm::vec3(float(a[0]), float(a[1]), float(a[2])); }

// Column-major like OpenGL: out[c][r] = m(r, c).
inline glm::mat4 toGlm(const Eigen::Matrix4d& m) {
  glm::mat4 out(1.0f);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = float(m(r, c));
  return out;
}

}  // namespace hermite::render
