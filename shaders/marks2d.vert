#version 450 core
// Anti-aliased 2D marks (sample dots, normal arrows, outlines): one instance per segment a–b in
// GL pixel coordinates (origin bottom-left), drawn as a quad around it
// (glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, n)). A dot is a segment with a = b.

layout(location = 0) in vec4 a_segment;      // (ax, ay, bx, by), pixels
layout(location = 1) in vec4 a_color_width;  // (r, g, b, full width in pixels)

uniform vec2 u_viewport;  // W, H in pixels

out vec4 v_segment;
out vec4 v_color_width;

void main() {
  float reach = 0.5 * a_color_width.w + 1.0;
  vec2 lo = min(a_segment.xy, a_segment.zw) - vec2(reach);
  vec2 hi = max(a_segment.xy, a_segment.zw) + vec2(reach);
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? hi.x : lo.x, (gl_VertexID & 2) != 0 ? hi.y : lo.y);
  v_segment = a_segment;
  v_color_width = a_color_width;
  gl_Position = vec4(corner / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}
