#pragma once
// The shading every 3D tracer uses (CPU reference here, GPU shaders through uniforms), so that
// images agree: base colour × (ambient + Σ Iₖ max(0, ns·Lₖ)), clamped to [0, 1], 8-bit =
// round(255·c). ns is the unit normal ∇f/‖∇f‖ flipped to face the viewer. Hits from inside
// (dot(∇f, ray direction) > 0) use the back colour, so inside-out regions stand out.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/base/geometry.h"

namespace hermite::shading {

inline constexpr std::array<double, 3> kFrontColor{0.85, 0.65, 0.40};
inline constexpr std::array<double, 3> kBackColor{0.35, 0.55, 0.85};
inline constexpr double kAmbient = 0.15;

// A directional light given in camera space: the direction towards the light is
// normalize(r·right + u·up + f·forward) with the camera's axes (r, u, f of camera.h).
struct Light {
  double r, u, f;
  double intensity;
};
inline constexpr std::array<Light, 2> kLights{{{0.4, 0.6, -0.7, 0.7}, {-0.6, -0.2, -0.5, 0.3}}};

// World-space unit direction towards light k for a camera with axes right, up, forward.
inline Vec<3> lightDirection(const Light& light, const Vec<3>& right, const Vec<3>& up, const Vec<3>& forward) {
  return (light.r * right + light.u * up + light.f * forward).normalized();
}

// Linear colour in [0, 1]³ of a hit with outward unit normal n (∇f/‖∇f‖) seen along the unit
// ray direction dir; right/up/forward are the camera axes.
inline Vec<3> shadeHit(const Vec<3>& n, const Vec<3>& dir, const Vec<3>& right, const Vec<3>& up,
                       const Vec<3>& forward) {
  const bool back = n.dot(dir) > 0;
  const Vec<3> ns = back ? Vec<3>(-n) : n;
  const std::array<double, 3>& base = back ? kBackColor : kFrontColor;
  double light = kAmbient;
  for (const Light& l : kLights) light += l.intensity * std::max(0.0, ns.dot(lightDirection(l, right, up, forward)));
  Vec<3> c;
  for (int k = 0; k < 3; ++k) c(k) = std::clamp(base[k] * light, 0.0, 1.0);
  return c;
}

// 8-bit channel: round(255·clamp(c, 0, 1)).
inline std::uint8_t toByte(double c) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(c, 0.0, 1.0)));
}

}  // namespace hermite::shading
