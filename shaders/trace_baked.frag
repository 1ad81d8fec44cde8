// Baked mode of the implicit tracer: f from an R³ R32F texture over the bounds (vertex-centred
// samples, trilinear filtering), per-brick (L, may contain a zero) from a brick texture.

uniform sampler3D uVolume;
uniform highp sampler3D uBricks;  // RGBA32F per brick: (L interpolant, cull flag, L field, field flag)
uniform vec3 uVolumeScale;        // (R − 1) / (hi − lo): world → sample index
uniform float uVolumeResolution;  // R
uniform vec3 uCell;               // sample spacing, world units

float fieldValue(vec3 p);
vec3 fieldGradient(vec3 p);
vec2 brickInfo(ivec3 b);

#include "trace_common.glsl"

float fieldValue(vec3 p) {
  vec3 u = ((p - uBoundsLo) * uVolumeScale + 0.5) / uVolumeResolution;
  return texture(uVolume, u).r;
}

// Central differences of the interpolant, one cell apart.
vec3 fieldGradient(vec3 p) {
  vec3 h = uCell;
  return vec3(fieldValue(p + vec3(h.x, 0, 0)) - fieldValue(p - vec3(h.x, 0, 0)),
              fieldValue(p + vec3(0, h.y, 0)) - fieldValue(p - vec3(0, h.y, 0)),
              fieldValue(p + vec3(0, 0, h.z)) - fieldValue(p - vec3(0, 0, h.z))) / (2.0 * h);
}

vec2 brickInfo(ivec3 b) { return texelFetch(uBricks, b, 0).xy; }

