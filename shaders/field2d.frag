#version 450 core
// The 2D field view (docs/maths.md, Colour map): heat map of f in the diverging colour map, iso-lines and the
// thick anti-aliased zero curve, from f and ∇f evaluated on the CPU (field2d_view.cpp).
// Drawn with fullscreen.vert. Line widths use the distance estimate |f − level| / ‖∇f‖ in pixels,
// with the same coverage ramp as the CPU reference (core/trace/field2d_reference.cpp).

uniform sampler2D u_field;      // RGBA32F (f, ∂f/∂x, ∂f/∂y, no data: 1 / 0), world units; GL row order (row 0 = bottom)
uniform vec2 u_viewport;        // W, H in pixels
uniform float u_pixel_size;     // world units per pixel
uniform float u_range;          // colour map covers [−range, range]
uniform float u_iso_spacing;    // ≤ 0: no iso-lines
uniform float u_zero_width;     // full width of the zero curve, pixels
uniform float u_iso_width;      // full width of an iso-line, pixels
uniform float u_iso_darken;     // iso-line colour = map colour × this
uniform vec3 u_zero_color;
uniform vec4 u_bounds_px;       // (x0, y0, x1, y1) GL pixel rectangle of view.bounds
uniform bool u_use_bounds;
uniform vec3 u_outside_color;   // the heat map fades towards it outside the bounds
uniform float u_outside_mix;
uniform vec3 u_no_data_color;   // no data: this grey, hatched diagonally (color_map.h, kNoDataColor)
uniform vec3 u_no_data_hatch_color;
uniform ivec2 u_no_data_hatch;  // (period, width) of the hatching in pixels

out vec4 frag_color;

#include "color_map.glsl"

// Coverage of a line of full width w at distance d pixels: a one-pixel linear ramp at its edge.
float coverage(float d, float w) { return clamp(0.5 * w + 0.5 - d, 0.0, 1.0); }

void main() {
  // One fetch for both grids (a ternary of texelFetch and texture would run both on llvmpipe):
  // on the pixel grid the sampler filters NEAREST, and a pixel centre's coordinate selects its texel.
  vec4 texel = texture(u_field, gl_FragCoord.xy / u_viewport);
  if (texel.w > 0.5) {  // no data: hatched grey, no lines
    ivec2 px = ivec2(gl_FragCoord.xy);
    bool hatch = (px.x + px.y) % u_no_data_hatch.x < u_no_data_hatch.y;
    frag_color = vec4(hatch ? u_no_data_hatch_color : u_no_data_color, 1.0);
    return;
  }
  vec3 s = texel.xyz;
  float v = s.x;
  float grad_px = length(s.yz) * u_pixel_size;  // change of f per pixel
  vec3 c = divergingColorAt(v / u_range);
  bool inside = !u_use_bounds || (gl_FragCoord.x >= u_bounds_px.x && gl_FragCoord.x <= u_bounds_px.z &&
                                  gl_FragCoord.y >= u_bounds_px.y && gl_FragCoord.y <= u_bounds_px.w);
  if (!inside) {
    frag_color = vec4(mix(c, u_outside_color, u_outside_mix), 1.0);
    return;
  }
  if (u_iso_spacing > 0.0) {
    float k = round(v / u_iso_spacing);
    if (k != 0.0 && grad_px > 0.0) {
      float cov = coverage(abs(v - k * u_iso_spacing) / grad_px, u_iso_width);
      c = mix(c, u_iso_darken * c, cov);
    }
  }
  float d0 = v == 0.0 ? 0.0 : (grad_px > 0.0 ? abs(v) / grad_px : 1e30);
  c = mix(c, u_zero_color, coverage(d0, u_zero_width));
  frag_color = vec4(c, 1.0);
}
