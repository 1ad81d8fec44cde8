#version 450 core
// Copies an RGBA8 image texel for texel onto a framebuffer of the same size (drawn with
// fullscreen.vert). The texture holds the image with row 0 = top (ImageRgba8 order), so rows flip.

uniform sampler2D u_image;
uniform int u_height;  // image height in pixels

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  frag_color = texelFetch(u_image, ivec2(p.x, u_height - 1 - p.y), 0);
}
