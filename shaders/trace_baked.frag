// Baked mode of the implicit tracer: f from an R³ R32F texture over the bounds (vertex-centred
// samples, trilinear filtering), per-brick (L, brick distance e) from a brick texture of its own
// (finer bricks than the bake's, ImplicitTracer::upload): e = 0 where the interpolant may vanish
// in the brick, else the Chebyshev distance in bricks to the nearest such brick.

uniform sampler3D uVolume;
// RGBA32F per (fine) brick: (L of the interpolant, brick distance e, L over the bricks b − 1 … b + 1, unused)
uniform highp sampler3D uBakedBricks;
uniform vec3 uVolumeScale;        // (R − 1) / (hi − lo): world → sample index
uniform float uVolumeResolution;  // R
uniform vec3 uCell;               // sample spacing, world units
// RGBA8 per sample: (n + 1) / 2, n the unit central difference one cell apart, and alpha 0 where
// a zero would be no surface (baked_normals.h)
uniform sampler3D uNormals;

#define TRACE_BRICK_DISTANCE 1
float fieldValue(vec3 p);
vec3 fieldGradient(vec3 p);
vec3 shadingDirection(vec3 p);
vec2 brickInfo(ivec3 b);
bool hasDataAt(vec3 p);

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

// The direction fieldGradient(p) gives, from one fetch: its vertex values filtered trilinearly
// are the same central difference (baked_normals.h); not unit length between samples.
vec3 shadingDirection(vec3 p) {
  vec3 u = ((p - uBoundsLo) * uVolumeScale + 0.5) / uVolumeResolution;
  vec3 n = texture(uNormals, u).xyz * 2.0 - 1.0;
  return length(n) < 0.01 ? vec3(0.0) : n;  // a texel of no direction decodes to (1/255, …)
}

vec2 brickInfo(ivec3 b) { return texelFetch(uBakedBricks, b, 0).xy; }

// Whether a zero at p is surface: with TRACE_NO_DATA (a bake with samples without data), the
// normals texture's alpha is 1 at samples where a zero would be surface, 0 where not
// (baked_normals.h); filtered, at least ½ nearer the former.
#ifdef TRACE_NO_DATA
bool hasDataAt(vec3 p) {
  vec3 u = ((p - uBoundsLo) * uVolumeScale + 0.5) / uVolumeResolution;
  return texture(uNormals, u).a >= 0.5;
}
#else
bool hasDataAt(vec3 p) { return true; }
#endif

float neighbourhoodLipschitz(ivec3 b) { return texelFetch(uBakedBricks, b, 0).z; }
