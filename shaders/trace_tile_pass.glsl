// Tile pass of the baked mode (included by trace_common.glsl with TRACE_TILE_PASS): one fragment
// per tile of TRACE_TILE × TRACE_TILE pixels marches a cone that holds every ray of the tile and
// writes how far along the tile's centre ray that cone is proven free of zeros of the baked
// interpolant inside the bounds (1e30: all the way through them). The full-resolution pass starts each ray there (uTileStart), so
// the long approach to a surface is marched once per tile instead of once per pixel.
//
// Why a pixel's ray may start at its own parameter tc: every ray of the tile leaves the eye
// (perspective; parallel to the centre ray in orthographic) at an angle whose tangent is at most
// uConeSlope from the centre ray, so its point at distance s lies at axial distance a ≤ s along
// the centre ray, within uConeRadius0 + uConeSlope·a of it. Every such point with a < tc is
// covered by the cone section proven empty below, or lies outside the bounds (the march starts
// where the cone, at its widest uConeReach, is still outside them), where zeros are never drawn.

uniform float uConeSlope;    // k (perspective; 0 in orthographic)
uniform float uConeRadius0;  // r0 (orthographic: the tile's half-diagonal in world units; 0 in perspective)
uniform float uConeReach;    // ≥ the cone's radius anywhere inside the bounds
float neighbourhoodLipschitz(ivec3 b);  // L of the interpolant over bricks b − 1 … b + 1

// The world box of bricks [first, last] (inclusive indices), with each face on the edge of the
// brick grid pushed out to infinity: outside the bounds the cone may go anywhere.
void brickRange(ivec3 first, ivec3 last, out vec3 lo, out vec3 hi) {
  lo = uBoundsLo + vec3(first) * uBrickSize;
  hi = uBoundsLo + vec3(last + 1) * uBrickSize;
  for (int k = 0; k < 3; ++k) {
    if (first[k] <= 0) lo[k] = -1e30;
    if (last[k] >= uBrickCount[k] - 1) hi[k] = 1e30;
  }
}

// Where the centre ray leaves the box [lo + ρ, hi − ρ] (so that cone sections of radius ≤ ρ
// about it stay inside [lo, hi]); t itself when o + t d is not inside that shrunk box.
float leaveShrunk(vec3 o, vec3 d, float t, vec3 lo, vec3 hi, float rho) {
  vec3 p = o + t * d;
  vec3 a = lo + rho, b = hi - rho;
  if (any(lessThan(p, a)) || any(greaterThan(p, b))) return t;
  return max(exitParameter(o, d, a, b), t);
}

void main() {
  vec3 o, d;
  pixelRay(o, d);
  outColor = vec4(1e30, 0.0, 0.0, 1.0);  // the tile's cone never meets the bounds
  float t0, t1;
  if (!clipBox(o, d, uBoundsLo - uConeReach, uBoundsHi + uConeReach, t0, t1)) return;
  float nudge = 1e-6 * length(uBoundsHi - uBoundsLo);
  float t = t0;
  bool stalled = false;
  for (int it = 0; it < uMaxSteps && !stalled && t < t1; ++it) {
    ivec3 b;
    vec2 info = brickAt(o, d, t, t1, nudge, b);
    float rho = uConeRadius0 + uConeSlope * t;
    float rhoEnd = uConeRadius0 + uConeSlope * t1;  // the widest section still ahead
    vec3 lo, hi;
    // (a) The empty cube of bricks of the brick distance map.
    float r = max(info.y - 1.0, 0.0);
    brickRange(b - ivec3(r), b + ivec3(r), lo, hi);
    float tCube = info.y > 0.5 ? leaveShrunk(o, d, t, lo, hi, rhoEnd) : t;
    // (b) A Lipschitz ball: sections up to ts lie within ρ + (1 + k)(ts − t) of o + t d, and inside
    // the bricks b − 1 … b + 1, where neighbourhoodLipschitz bounds the interpolant's slope.
    brickRange(b - 1, b + 1, lo, hi);
    float L = neighbourhoodLipschitz(b);  // +inf where a sample is NaN
    float fa = abs(fieldValue(o + t * d));
    float ball = L > 0.0 ? (fa / L - rho) / (1.0 + uConeSlope) : (fa > 0.0 ? 1e30 : 0.0);
    if (!(ball > 0.0)) ball = 0.0;  // NaN proves nothing
    float tBall = min(t + ball, leaveShrunk(o, d, t, lo, hi, rhoEnd));
    float tNext = min(max(tCube, tBall), t1);
    // Creeping towards a surface (or a cone as wide as the bricks): the pixels take over.
    stalled = tNext < t + uMinStep;
    if (!stalled) t = tNext;
  }
  // Through the bounds without a stall: no ray of the tile meets a zero inside them, and the
  // trace pass skips the tile (tile_spans.h, kEmptyTile).
  outColor = vec4((!stalled && t >= t1) ? 1e30 : t, 0.0, 0.0, 1.0);
}
