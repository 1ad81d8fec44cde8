// The diverging colour map of core/trace/color_map.h (kDivergingStops), for the 2D field view and the
// slice plane. The stops are compile-time constants, not uniforms: llvmpipe re-reads uniforms for
// every fragment vector and cannot fold the divisions by the stop spacing (docs/performance.md,
// 2D view). tests/render/test_color_map_glsl.cpp checks these numbers against kDivergingStops.
const vec4 kDivergingStops[5] = vec4[5](vec4(-1.0, 0.085, 0.250, 0.600),  // (t, r, g, b)
                                        vec4(-0.5, 0.420, 0.620, 0.860),
                                        vec4(0.0, 0.965, 0.965, 0.965),
                                        vec4(0.5, 0.860, 0.620, 0.420),
                                        vec4(1.0, 0.600, 0.250, 0.085));

// Colour at the normalised position t (clamped to [−1, 1]); NaN gives mid grey. Piecewise linear
// between the stops, written as a sum of clamped ramps (no loop, no dynamic indexing: several
// times faster on llvmpipe than the loop, same values).
vec3 divergingColorAt(float t) {
  if (isnan(t)) return vec3(0.5);
  t = clamp(t, -1.0, 1.0);
  vec3 c = kDivergingStops[0].yzw;
  for (int k = 0; k < 4; ++k) {  // unrolled by the compiler: constant bounds and indices
    vec4 a = kDivergingStops[k], b = kDivergingStops[k + 1];
    c += (b.yzw - a.yzw) * clamp((t - a.x) / (b.x - a.x), 0.0, 1.0);
  }
  return c;
}
