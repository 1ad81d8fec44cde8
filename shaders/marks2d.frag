#version 450 core
// Coverage of the segment of marks2d.vert at this pixel centre (same ramp as the CPU reference:
// clamp(w/2 + 1/2 − d, 0, 1)), output as alpha for blending.

in vec4 v_segment;
in vec4 v_color_width;

out vec4 frag_color;

void main() {
  vec2 p = gl_FragCoord.xy;
  vec2 a = v_segment.xy;
  vec2 ab = v_segment.zw - a;
  float len2 = dot(ab, ab);
  float s = len2 > 0.0 ? clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  float d = length(p - (a + s * ab));
  float cov = clamp(0.5 * v_color_width.w + 0.5 - d, 0.0, 1.0);
  if (cov <= 0.0) discard;
  frag_color = vec4(v_color_width.rgb, cov);
}
