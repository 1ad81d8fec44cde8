// Shared ray marcher of trace_baked.frag and trace_exact.frag (included after the including file
// defined fieldValue(p), fieldGradient(p), shadingDirection(p) — ∇f or a vector along it, 0 where
// there is none —, brickInfo(b) = (L, may contain a zero) and hasDataAt(p), whether a zero at p
// is surface).
// Rays follow core/trace/camera.h exactly (Camera::ray); world units throughout.

layout(location = 0) out vec4 outColor;  // final colour (surface, slice plane or background)
layout(location = 1) out vec4 outHit;    // (t of the surface hit or -1, outward unit normal)
layout(location = 2) out vec4 outPlane;  // slice-plane colour, alpha 1 where the plane is hit

uniform vec2 uViewport;  // W, H in pixels
uniform vec3 uEye;
uniform vec3 uRight;
uniform vec3 uUp;
uniform vec3 uForward;
uniform float uTileSize;    // pixels per fragment edge: 1, or TRACE_TILE in the tile pass (trace_tile_pass.glsl)
uniform float uTanHalf;     // tan(fov_y / 2)
uniform float uAspect;      // W / H
uniform float uHalfHeight;  // orthographic half height, world units
uniform int uOrtho;
uniform mat4 uViewProj;     // P(near, far) · V, for gl_FragDepth

uniform vec3 uBoundsLo;
uniform vec3 uBoundsHi;
uniform ivec3 uBrickCount;
uniform vec3 uBrickSize;
uniform float uMinStep;     // ε of the march, world units
uniform int uMaxSteps;
// Loop iterations one pixel may spend on the march (fieldValue counts its own loops into gLoops).
// Mesa's software rasterisers (llvmpipe, softpipe) end every loop of a shader invocation once
// 65 535 iterations of all its loops together have run, so a long march over many centres would
// silently evaluate a truncated field; past this budget the pixel is reported undecided instead
// (t = −2 in outHit) and the CPU traces it. Other drivers get a budget that never binds.
uniform int uLoopBudget;
int gLoops = 0;
uniform int uShowSurface;
uniform vec3 uBackground;   // exact bytes / 255

// core/trace/shading.h
uniform vec3 uFrontColor;
uniform vec3 uBackColor;
uniform float uAmbient;
uniform vec3 uLightDir[2];  // world-space unit directions towards the lights
uniform float uLightIntensity[2];

// Slice plane and core/trace/color_map.h (the stops: color_map.glsl)
uniform int uSliceEnabled;
uniform vec3 uSliceNormal;  // unit
uniform float uSliceOffset;
uniform float uSliceRange;
uniform float uIsoSpacing;
uniform vec3 uZeroColor;
uniform float uIsoDarken;

// The ray through the centre of this fragment's pixel, or of its tile of uTileSize² pixels.
void pixelRay(out vec3 origin, out vec3 dir) {
  float px = gl_FragCoord.x * uTileSize;
  float py = uViewport.y - gl_FragCoord.y * uTileSize;  // row 0 = top
  float sx = (2.0 * px / uViewport.x - 1.0) * uAspect;
  float sy = 1.0 - 2.0 * py / uViewport.y;
  if (uOrtho == 1) {
    origin = uEye + (sx * uHalfHeight) * uRight + (sy * uHalfHeight) * uUp;
    dir = uForward;
  } else {
    origin = uEye;
    dir = normalize(uForward + (sx * uTanHalf) * uRight + (sy * uTanHalf) * uUp);
  }
}

// [t0, t1] of the ray inside the box (t ≥ 0); false when it misses.
bool clipBox(vec3 o, vec3 d, vec3 lo, vec3 hi, out float t0, out float t1) {
  t0 = 0.0;
  t1 = 1e30;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    float ta = (lo[k] - o[k]) / d[k];
    float tb = (hi[k] - o[k]) / d[k];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return t0 <= t1;
}

// Where the ray leaves the box (1e30 when it runs parallel to every face it could leave by).
// Vector selects, no branches: llvmpipe would execute both sides of each anyway.
float exitParameter(vec3 o, vec3 d, vec3 lo, vec3 hi) {
  vec3 te = (mix(lo, hi, greaterThan(d, vec3(0.0))) - o) / d;
  te = mix(te, vec3(1e30), equal(d, vec3(0.0)));
  return min(te.x, min(te.y, te.z));
}

// Empty cube of bricks around brick b that the ray at o + t d leaves at the returned parameter
// (clamped to [t + nudge, t1]); info = brickInfo(b) in (L, e) form: e = 0 when the brick may
// contain a zero, else every brick within Chebyshev distance e − 1 of b is free of zeros.
float leaveBricks(vec3 o, vec3 d, float t, float t1, float nudge, ivec3 b, vec2 info) {
  float r = max(info.y - 1.0, 0.0);  // the cube [b − r, b + r], or the brick itself (e = 0)
  vec3 blo = uBoundsLo + (vec3(b) - r) * uBrickSize;
  vec3 bhi = uBoundsLo + (vec3(b) + r + 1.0) * uBrickSize;
  return min(max(exitParameter(o, d, blo, bhi), t + nudge), t1);
}

// The brick of the point at t (a nudge past it, so a ray on a brick face looks ahead) and its
// (L, e) as leaveBricks takes it.
vec2 brickAt(vec3 o, vec3 d, float t, float t1, float nudge, out ivec3 b) {
  vec3 p = o + min(t + nudge, t1) * d;
  b = clamp(ivec3(floor((p - uBoundsLo) / uBrickSize)), ivec3(0), uBrickCount - 1);
  vec2 info = brickInfo(b);
#ifndef TRACE_BRICK_DISTANCE
  info.y = info.y > 0.5 ? 0.0 : 1.0;  // (L, may contain a zero) → (L, e) with e ∈ {0, 1}
#endif
  return info;
}

// The first zero of f on [t0, t1], in two loops.
// 1. Skip: leave the zero-free bricks in front of the first brick that may hold a zero, from the
//    brick texture alone. f is not needed there, and it is the expensive fetch (a trilinear 3D
//    read is 8 texel reads on llvmpipe, an exact evaluation N kernel terms), which a single
//    loop would pay on every lane of a SIMD vector while any lane still skips.
// 2. March: brick by brick, jumping over empty space; in bricks that may hold a zero, steps of
//    |f|/L + ε: the Lipschitz bound proves [t, t + |f|/L) free of zeros, and the sign test alone
//    covers the ε beyond it, so a zero pair closer together than ε may pass unseen there (as
//    between any two samples ε apart) but a single zero never does. Plain |f|/L steps would
//    creep towards a surface the ray meets at a shallow angle in steps of ε. Then a secant on
//    the first sign change,
//    kept inside the unproven ε (the interpolant is nearly linear over ε; settled views are
//    refined against the true field on the CPU anyway).
// With TRACE_BRICK_DISTANCE, brickInfo(b) = (L, e) as leaveBricks takes it (a "brick distance
// map": the ray leaves a whole empty cube of bricks in one step); without it, brickInfo(b) =
// (L, 1 where the brick may contain a zero, else 0).
// One fetch of each kind per iteration and no return inside the loops: llvmpipe runs both sides
// of divergent branches under masks, so every fetch sits on the common path, control flow stays
// simple, and a loop ends as soon as all lanes are done.
bool march(vec3 o, vec3 d, float t0, float t1, out float tHit, out bool undecided) {
  float nudge = 1e-6 * length(uBoundsHi - uBoundsLo);
  float t = t0;
  int it = 0;
  bool nearZero = false;
  for (; it < uMaxSteps && gLoops < uLoopBudget && !nearZero && t < t1; ++it) {
    // An upper bound on the loop iterations this one runs: 1 since exitParameter has no axis
    // loop any more; the 4 it counted then stays (a budget may only overcount).
    gLoops += 4;
    ivec3 b;
    vec2 info = brickAt(o, d, t, t1, nudge, b);
    nearZero = info.y < 0.5;
    if (!nearZero) t = leaveBricks(o, d, t, t1, nudge, b, info);
  }
  float fa = fieldValue(o + t * d);
  bool negA = fa < 0.0;
  float tb = t, fb = fa;
  float tFree = t;  // the first zero lies in [tFree, tb]
  bool found = fa == 0.0;
  for (; it < uMaxSteps && gLoops < uLoopBudget && !found && t < t1; ++it) {
    gLoops += 4;  // as above
    ivec3 b;
    vec2 info = brickAt(o, d, t, t1, nudge, b);
    float tExit = leaveBricks(o, d, t, t1, nudge, b, info);
    float stepLength = (info.y > 0.5) ? 1e30 : (info.x > 0.0 ? abs(fa) / info.x : 1e30);
    float ts = min(t + stepLength + uMinStep, tExit);  // tExit ≤ t1
    float fs = fieldValue(o + ts * d);
    bool surface = fs == 0.0 || (fs < 0.0) != negA;
    // A zero where the field has no data (at the secant point) is passed: the march goes on
    // with the sign beyond it. Only on a sign change, which few iterations of a SIMD group see.
    if (surface) surface = hasDataAt(o + mix(t, ts, fa == 0.0 ? 0.0 : clamp(fa / (fa - fs), 0.0, 1.0)) * d);
    if (surface) {
      found = true;
      tFree = min(t + stepLength, ts);
      tb = ts;
      fb = fs;
    } else {
      t = ts;
      fa = fs;
      negA = fs < 0.0;
    }
  }
  undecided = !found && t < t1;  // out of steps or budget before the end of the ray
  // Secant on the bracket [t, tb] (fa, fb of opposite signs, or fb = 0), kept in [tFree, tb].
  float w = fa == 0.0 ? 0.0 : fa / (fa - fb);
  tHit = clamp(mix(t, tb, clamp(w, 0.0, 1.0)), tFree, tb);
  return found;
}

vec3 shadeHit(vec3 n, vec3 d) {
  bool back = dot(n, d) > 0.0;
  vec3 ns = back ? -n : n;
  vec3 base = back ? uBackColor : uFrontColor;
  float light = uAmbient;
  for (int k = 0; k < 2; ++k) light += uLightIntensity[k] * max(0.0, dot(ns, uLightDir[k]));
  return clamp(base * light, 0.0, 1.0);
}

#include "color_map.glsl"

vec3 divergingColor(float f) { return divergingColorAt(f / uSliceRange); }

#ifdef TRACE_SLICE
// Heat map, iso-lines and zero curve at a plane point p seen at ray parameter t along d.
vec3 sliceColor(vec3 p, float t, vec3 d) {
  float f = fieldValue(p);
  vec3 g = fieldGradient(p);
  vec3 gPlane = g - dot(g, uSliceNormal) * uSliceNormal;
  // World size of one pixel at this depth, stretched by the plane's tilt.
  float pixelWorld = (uOrtho == 1 ? 2.0 * uHalfHeight : 2.0 * uTanHalf * t * dot(d, uForward)) / uViewport.y;
  float footprint = pixelWorld / max(abs(dot(d, uSliceNormal)), 0.05);
  float dfPixel = max(length(gPlane) * footprint, 1e-30);
  if (abs(f) < dfPixel) return uZeroColor;  // the zero curve, 2 px wide
  vec3 c = divergingColor(f);
  float k = round(f / uIsoSpacing);
  if (k != 0.0 && abs(f - k * uIsoSpacing) < 0.5 * dfPixel) c *= uIsoDarken;
  return c;
}

#endif

float windowDepth(vec3 p) {
  vec4 clip = uViewProj * vec4(p, 1.0);
  return clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
}

#ifdef TRACE_TILE_PASS
#include "trace_tile_pass.glsl"
#else
#ifdef TRACE_TILE_START
// Per tile of TRACE_TILE² pixels, a ray parameter before which none of its rays meets a zero
// inside the bounds (trace_tile_pass.glsl): the march starts there.
uniform sampler2D uTileStart;
#endif

void main() {
  vec3 o, d;
  pixelRay(o, d);
  outColor = vec4(uBackground, 1.0);
  outHit = vec4(-1.0, 0.0, 0.0, 0.0);
  outPlane = vec4(0.0);
  gl_FragDepth = 1.0;
  float t0, t1;
  if (!clipBox(o, d, uBoundsLo, uBoundsHi, t0, t1)) return;

  float tSurface = 1e30;
  bool surface = false;
  if (uShowSurface == 1) {
    float tHit;
    bool undecided;
    float tStart = t0;
#ifdef TRACE_TILE_START
    tStart = max(t0, texelFetch(uTileStart, ivec2(gl_FragCoord.xy) / TRACE_TILE, 0).r);
#endif
    if (march(o, d, tStart, t1, tHit, undecided)) {
      surface = true;
      tSurface = tHit;
      vec3 p = o + tHit * d;
      vec3 g = shadingDirection(p);
      float gn = length(g);
      vec3 n = gn > 0.0 ? g / gn : -d;
      outHit = vec4(tHit, n);
      outColor = vec4(shadeHit(n, d), 1.0);
      gl_FragDepth = windowDepth(p);
    } else if (undecided) {
      outHit = vec4(-2.0, 0.0, 0.0, 0.0);
    }
  }
#ifdef TRACE_SLICE
  if (uSliceEnabled == 1) {
    float dn = dot(d, uSliceNormal);
    if (dn != 0.0) {
      float tp = (uSliceOffset - dot(uSliceNormal, o)) / dn;
      if (tp >= t0 && tp <= t1) {
        vec3 p = o + tp * d;
        vec3 c = sliceColor(p, tp, d);
        outPlane = vec4(c, 1.0);
        if (tp < tSurface) {
          outColor = vec4(c, 1.0);
          gl_FragDepth = windowDepth(p);
        }
      }
    }
  }
#endif
}
#endif
