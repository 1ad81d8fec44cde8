#version 450 core
// Rectangles of pixels (two triangles each, render/tile_spans.h): aPixel is a pixel corner in GL
// window coordinates (x right, y up, (0, 0) the bottom-left corner of the viewport).

layout(location = 0) in vec2 aPixel;
uniform vec2 uViewport;  // W, H in pixels

void main() { gl_Position = vec4(2.0 * aPixel / uViewport - 1.0, 0.0, 1.0); }
