/* What a frame's view image costs llvmpipe (docs/performance.md, "GUI frame"): a clear of a
 * 1280 × 800 OSMesa buffer and one opaque 960 × 760 textured quad, drawn as ImGui draws the view
 * image (vertex colour times texel), 100 times with a glFinish each; or the same image copied by
 * glBlitFramebuffer. Prints the mean wall time per frame.
 *
 * Build: gcc -O2 scripts/view_quad_cost.c -o /tmp/view_quad_cost -lOSMesa
 * Usage: /tmp/view_quad_cost FILTER [MODE]   FILTER: linear | nearest;
 *        MODE: quad (default) | blit | blit-flipped. LP_NUM_THREADS=1 gives one rasteriser thread. */
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

static const char* kVertex =
    "#version 330 core\nlayout(location=0) in vec2 p; layout(location=1) in vec2 uv; layout(location=2) in vec4 c;"
    "out vec2 U; out vec4 C; void main() { U = uv; C = c; gl_Position = vec4(p, 0, 1); }";
static const char* kFragment =
    "#version 330 core\nin vec2 U; in vec4 C; uniform sampler2D T; out vec4 o; void main() { o = C * texture(T, U.st); }";

static void useProgram(void) {
  GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER), p = glCreateProgram();
  glShaderSource(v, 1, &kVertex, 0);
  glCompileShader(v);
  glShaderSource(f, 1, &kFragment, 0);
  glCompileShader(f);
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glUseProgram(p);
}

/* The view image's quad: right of a 320-pixel panel column, at the image's own size. */
static void bindQuad(int W, int H, int tw, int th) {
  const float x0 = -1 + 2.0f * 320 / W, x1 = 1, y0 = -1, y1 = -1 + 2.0f * th / H;
  const float q[] = {x0, y0, 0, 1, 1, 1, 1, 1, x1, y0, 1, 1, 1, 1, 1, 1, x1, y1, 1, 0, 1, 1, 1, 1,
                     x0, y0, 0, 1, 1, 1, 1, 1, x1, y1, 1, 0, 1, 1, 1, 1, x0, y1, 0, 0, 1, 1, 1, 1};
  GLuint vao, vbo;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, sizeof q, q, GL_STATIC_DRAW);
  for (int a = 0; a < 3; ++a) glEnableVertexAttribArray(a);
  glVertexAttribPointer(0, 2, GL_FLOAT, 0, 32, (void*)0);
  glVertexAttribPointer(1, 2, GL_FLOAT, 0, 32, (void*)8);
  glVertexAttribPointer(2, 4, GL_FLOAT, 0, 32, (void*)16);
}

int main(int argc, char** argv) {
  const int W = 1280, H = 800, tw = 960, th = 760;
  if (argc < 2) return fprintf(stderr, "usage: %s linear|nearest [quad|blit|blit-flipped]\n", argv[0]), 2;
  const int nearest = strcmp(argv[1], "nearest") == 0;
  const char* mode = argc > 2 ? argv[2] : "quad";
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, NULL);
  unsigned char* buffer = malloc((size_t)W * H * 4);
  unsigned char* image = malloc((size_t)tw * th * 4);
  if (!ctx || !buffer || !image || !OSMesaMakeCurrent(ctx, buffer, GL_UNSIGNED_BYTE, W, H)) return 1;
  for (size_t i = 0; i < (size_t)tw * th * 4; ++i) image[i] = (unsigned char)rand();
  useProgram();
  GLuint tex, fbo;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tw, th, 0, GL_RGBA, GL_UNSIGNED_BYTE, image);
  const GLint filter = nearest ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  bindQuad(W, H, tw, th);
  glViewport(0, 0, W, H);
  double t0 = 0;
  for (int i = 0; i < 105; ++i) {
    if (i == 5) t0 = now();  /* five frames to warm up */
    glClear(GL_COLOR_BUFFER_BIT);
    if (strcmp(mode, "blit") == 0)
      glBlitFramebuffer(0, 0, tw, th, 320, 0, 320 + tw, th, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    else if (strcmp(mode, "blit-flipped") == 0)
      glBlitFramebuffer(0, 0, tw, th, 320, th, 320 + tw, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    else
      glDrawArrays(GL_TRIANGLES, 0, 6);
    glFinish();
  }
  printf("%s %s: %.2f ms per frame\n", argv[1], mode, (now() - t0) * 1000 / 100);
  return 0;
}
