#include "render/implicit_tracer.h"
#include "core/base/ms_since.h"
#include "render/gl/gl_loader.h"
#include "render/gl/glm_convert.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include <Eigen/Geometry>

#include "core/base/errors.h"
#include "core/rbf/similarity_transform.h"
#include "core/trace/color_map.h"
#include "core/trace/mark_sizes.h"
#include "core/trace/shading.h"
#include "render/baked_normals.h"
#include "render/gl/gl_objects.h"
#include "render/gl/shader_library.h"
#include "render/hit_refinement.h"
#include "render/kernel_shader_defines.h"
#include "render/overlay.h"
#include "render/staged_volume_upload.h"
#include "render/tile_spans.h"

namespace hermite::render {

namespace {

using Clock = std::chrono::steady_clock;

// Two unit vectors spanning the plane with unit normal n.
void planeBasis(const Vec<3>& n, Vec<3>& u, Vec<3>& v) {
  const Vec<3> a = std::abs(n.x()) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY();
  u = n.cross(a).normalized();
  v = n.cross(u);
}

// Per-brick (L of the interpolant and field, interpolant may vanish, L field, field may vanish).
// The trilinear interpolant's gradient component k in a cell is a convex combination of the
// cell's edge differences along k divided by h_k, so ‖∇‖ ≤ ‖(max|Δₖf|/hₖ)ₖ‖ over the brick.
std::vector<float> brickTexels(const VolumeBake& bake) {
  const BrickGrid& grid = bake.bricks;
  const int n = grid.brickCount();
  const int R = bake.resolution, C = bake.brickCells;
  const Vec<3> h = bake.spacing();
  std::vector<float> texels(4 * std::size_t(n));
#pragma omp parallel for schedule(static)
  for (int b = 0; b < n; ++b) {
    const int bx = b % grid.count.x(), by = (b / grid.count.x()) % grid.count.y(),
              bz = b / (grid.count.x() * grid.count.y());
    const int i0 = bx * C, i1 = std::min((bx + 1) * C, R - 1);
    const int j0 = by * C, j1 = std::min((by + 1) * C, R - 1);
    const int k0 = bz * C, k1 = std::min((bz + 1) * C, R - 1);
    double maxDiff[3] = {0, 0, 0};
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const double f = bake.value(i, j, k);
          if (i < i1) maxDiff[0] = std::max(maxDiff[0], std::abs(double(bake.value(i + 1, j, k)) - f));
          if (j < j1) maxDiff[1] = std::max(maxDiff[1], std::abs(double(bake.value(i, j + 1, k)) - f));
          if (k < k1) maxDiff[2] = std::max(maxDiff[2], std::abs(double(bake.value(i, j, k + 1)) - f));
        }
    const double interp = Vec<3>(maxDiff[0] / h.x(), maxDiff[1] / h.y(), maxDiff[2] / h.z()).norm();
    const double field = grid.lipschitz[b];
    // Float texture values: 1 % slack covers rounding of the filtered samples.
    // The shader steps on the interpolant, so its own bound is the safe and tight one; the
    // field's bound (often orders of magnitude above the true ‖∇f‖ for global kernels) would
    // only shrink the steps. The true field is handled by the exact refinement.
    const double L = 1.01 * interp;
    texels[4 * std::size_t(b) + 0] = float(L);
    texels[4 * std::size_t(b) + 1] = bake.interpolantMayContainZero(b) ? 1.0f : 0.0f;
    texels[4 * std::size_t(b) + 2] = float(field);
    texels[4 * std::size_t(b) + 3] = grid.mayContainZero[b] ? 1.0f : 0.0f;
  }
  return texels;
}

// The baked mode's own brick grid (finer than the bake's, so that culling hugs the surface and
// L is tighter): per brick (L, e) with L = 1.01 × the trilinear interpolant's Lipschitz bound on
// the brick (see brickTexels) and e the brick distance: 0 where the interpolant may vanish in the
// brick (its samples do not all have one sign), else the Chebyshev distance in bricks to the
// nearest such brick, so that every brick within e − 1 of it is free of zeros too.
// A third channel holds the largest L over the bricks b − 1 … b + 1 (those in the grid; +inf
// where any of them has a NaN sample) for the tile pass's cone, whose sections straddle bricks.
struct BakedBricks {
  Eigen::Array3i count = Eigen::Array3i::Zero();
  Vec<3> size = Vec<3>::Zero();
  // RGBA per brick, x fastest; A unused: llvmpipe fetches 3-channel float textures through a
  // slow generic path (field2d_view.cpp avoids them for the same reason)
  std::vector<float> texels;
};

// Cells per brick edge of the baked mode's brick grid.
constexpr int kBakedBrickCells = 4;

// Chebyshev distance transform of a perAxis³ grid (x fastest), in place and separable: pass k
// sets d(x) = min_y max(|x_k − y_k|, d(y)) along the lines of axis k.
void chebyshevDistance(std::vector<int>& dist, int perAxis) {
  std::vector<int> line(perAxis), result(perAxis);
  const int stride[3] = {1, perAxis, perAxis * perAxis};
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    for (int u = 0; u < perAxis; ++u)
      for (int w = 0; w < perAxis; ++w) {
        const int base = u * stride[a1] + w * stride[a2];
        for (int q = 0; q < perAxis; ++q) line[q] = dist[base + q * stride[axis]];
        for (int q = 0; q < perAxis; ++q) {
          int best = line[q];
          for (int r = 0; r < perAxis; ++r) best = std::min(best, std::max(std::abs(q - r), line[r]));
          result[q] = best;
        }
        for (int q = 0; q < perAxis; ++q) dist[base + q * stride[axis]] = result[q];
      }
  }
}

BakedBricks bakedBrickTexels(const VolumeBake& bake, int C) {
  const int R = bake.resolution;
  const int perAxis = (R - 1 + C - 1) / C;
  const Vec<3> h = bake.spacing();
  BakedBricks out;
  out.count = Eigen::Array3i::Constant(perAxis);
  out.size = double(C) * h;
  const int n = perAxis * perAxis * perAxis;
  out.texels.assign(4 * std::size_t(n), 0.0f);
  constexpr int kFar = 1 << 20;
  std::vector<int> dist(n);
  std::vector<float> lipschitz(n);  // +inf for bricks with a NaN sample
  const std::size_t plane = std::size_t(R) * R;
  const float* v = bake.values.data();
#pragma omp parallel for schedule(static)
  for (int b = 0; b < n; ++b) {
    const int bx = b % perAxis, by = (b / perAxis) % perAxis, bz = b / (perAxis * perAxis);
    const int i0 = bx * C, i1 = std::min((bx + 1) * C, R - 1);
    const int j0 = by * C, j1 = std::min((by + 1) * C, R - 1);
    const int k0 = bz * C, k1 = std::min((bz + 1) * C, R - 1);
    double maxDiff[3] = {0, 0, 0};
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    bool nan = false;
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j) {
        const float* row = v + plane * k + std::size_t(R) * j;
        for (int i = i0; i <= i1; ++i) {
          const double f = row[i];
          nan = nan || std::isnan(row[i]);
          lo = std::min(lo, row[i]);
          hi = std::max(hi, row[i]);
          if (i < i1) maxDiff[0] = std::max(maxDiff[0], std::abs(double(row[i + 1]) - f));
          if (j < j1) maxDiff[1] = std::max(maxDiff[1], std::abs(double(row[i + R]) - f));
          if (k < k1) maxDiff[2] = std::max(maxDiff[2], std::abs(double(row[i + plane]) - f));
        }
      }
    const double interp = Vec<3>(maxDiff[0] / h.x(), maxDiff[1] / h.y(), maxDiff[2] / h.z()).norm();
    out.texels[4 * std::size_t(b)] = float(1.01 * interp);  // 1 % slack as in brickTexels
    lipschitz[b] = nan ? std::numeric_limits<float>::infinity() : float(1.01 * interp);
    dist[b] = (nan || (lo <= 0.0f && hi >= 0.0f)) ? 0 : kFar;
  }
#pragma omp parallel for schedule(static)
  for (int b = 0; b < n; ++b) {
    const int bx = b % perAxis, by = (b / perAxis) % perAxis, bz = b / (perAxis * perAxis);
    float L = 0;
    for (int z = std::max(bz - 1, 0); z <= std::min(bz + 1, perAxis - 1); ++z)
      for (int y = std::max(by - 1, 0); y <= std::min(by + 1, perAxis - 1); ++y)
        for (int x = std::max(bx - 1, 0); x <= std::min(bx + 1, perAxis - 1); ++x)
          L = std::max(L, lipschitz[(z * perAxis + y) * perAxis + x]);
    out.texels[4 * std::size_t(b) + 2] = L;
  }
  chebyshevDistance(dist, perAxis);
  for (int b = 0; b < n; ++b) out.texels[4 * std::size_t(b) + 1] = float(std::min(dist[b], 4 * perAxis));
  return out;
}



// Polynomial coefficients (order 1, x, y, z, xx, xy, xz, yy, yz, zz) re-expressed for
// x = o + y (y the shifted coordinate): p(o + y) as a polynomial in y, i.e. the core's
// transformPolynomial for the translation y = x − o; unused entries stay 0.
std::array<double, 10> shiftPolynomial(Polynomial p, const Eigen::VectorXd& c, const Vec<3>& o) {
  Similarity<3> toShifted;
  toShifted.t = -o;
  const Eigen::VectorXd shifted = transformPolynomial<3>(p, c, toShifted);
  std::array<double, 10> s{};
  for (Eigen::Index k = 0; k < shifted.size(); ++k) s[k] = shifted(k);
  return s;
}

// Pixels per tile edge of the baked mode's tile pass (trace_tile_pass.glsl): the shaders get it
// as TRACE_TILE.
constexpr int kTraceTile = 4;

// An FBO with colour (RGBA8), hit data (RGBA32F), plane colour (RGBA8) and depth, and the tile
// pass's own single-channel target.
struct TraceTarget {
  int width = 0, height = 0;
  GLuint fbo = 0;
  Texture color, hit, plane, depth;
  // The tile pass's output: per tile of kTraceTile² pixels, where its rays may start (R32F).
  int tileWidth = 0, tileHeight = 0;
  GLuint tileFbo = 0;
  Texture tileStart;

  TraceTarget(int w, int h)
      : width(w), height(h), tileWidth((w + kTraceTile - 1) / kTraceTile), tileHeight((h + kTraceTile - 1) / kTraceTile) {
    tileStart = Texture::create2D(GL_R32F, tileWidth, tileHeight);
    tileStart.setFilter(GL_NEAREST, GL_NEAREST);
    glCreateFramebuffers(1, &tileFbo);
    glNamedFramebufferTexture(tileFbo, GL_COLOR_ATTACHMENT0, tileStart.id(), 0);
    if (glCheckNamedFramebufferStatus(tileFbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw EnvironmentError("implicit tracer: incomplete tile framebuffer");
    color = Texture::create2D(GL_RGBA8, w, h);
    hit = Texture::create2D(GL_RGBA32F, w, h);
    plane = Texture::create2D(GL_RGBA8, w, h);
    depth = Texture::create2D(GL_DEPTH_COMPONENT24, w, h);
    for (Texture* t : {&color, &hit, &plane, &depth}) t->setFilter(GL_NEAREST, GL_NEAREST);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color.id(), 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, hit.id(), 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT2, plane.id(), 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth.id(), 0);
    setAllBuffers();
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw EnvironmentError("implicit tracer: incomplete framebuffer");
    checkGl("implicit tracer framebuffer");
  }
  ~TraceTarget() {
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (tileFbo) glDeleteFramebuffers(1, &tileFbo);
  }
  TraceTarget(const TraceTarget&) = delete;
  TraceTarget& operator=(const TraceTarget&) = delete;

  void setAllBuffers() const {
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(fbo, 3, buffers);
  }
  // What the trace pass writes where a ray misses everything: the background (exact bytes, as
  // uBackground), no hit (t = −1), no plane, far depth.
  void clearToMiss(const std::array<double, 3>& background) const {
    const float missColor[4] = {shading::toByte(background[0]) / 255.0f, shading::toByte(background[1]) / 255.0f,
                                shading::toByte(background[2]) / 255.0f, 1.0f};
    const float noHit[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
    const float noPlane[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, missColor);
    glClearNamedFramebufferfv(fbo, GL_COLOR, 1, noHit);
    glClearNamedFramebufferfv(fbo, GL_COLOR, 2, noPlane);
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far);
  }
  void setColorOnly() const {
    const GLenum buffers[1] = {GL_COLOR_ATTACHMENT0};
    glNamedFramebufferDrawBuffers(fbo, 1, buffers);
  }
  void bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
  }
  void bindTiles() const {
    glBindFramebuffer(GL_FRAMEBUFFER, tileFbo);
    glViewport(0, 0, tileWidth, tileHeight);
  }
};

// Reads a whole level-0 texture; rows come bottom-up (GL order).
template <class T>
std::vector<T> readTexture(const Texture& texture, GLenum format, GLenum type, std::size_t componentsPerPixel) {
  std::vector<T> data(std::size_t(texture.width()) * texture.height() * componentsPerPixel);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture.id(), 0, format, type, GLsizei(data.size() * sizeof(T)), data.data());
  checkGl("glGetTextureImage");
  return data;
}

// Trace programs: baked, exact in float, exact in double, and the baked mode's tile pass.
enum TraceProgramKind { kBakedProgram = 0, kExactFloatProgram = 1, kExactDoubleProgram = 2, kBakedTileProgram = 3 };
constexpr int kTraceProgramKinds = 4;

// The trace program of a kind, with or without the slice plane, and (baked) with or without the
// test of zeros without data (compile-time switches: llvmpipe executes untaken branches under a
// mask, so an unused slice or data test would still cost its fetches: the test alone made the
// baked trace of a field with data everywhere a quarter slower).
Program buildTraceProgram(TraceProgramKind kind, bool slice, bool noData) {
  const bool baked = kind == kBakedProgram || kind == kBakedTileProgram;
  const char* file = baked ? "trace_baked.frag" : "trace_exact.frag";
  std::string fragment = kernelShaderDefines();
  if (slice) fragment += "#define TRACE_SLICE 1\n";
  if (noData && baked) fragment += "#define TRACE_NO_DATA 1\n";
  if (kind == kExactDoubleProgram) fragment += "#define EXACT_DOUBLE 1\n";
  if (baked) fragment += "#define TRACE_TILE " + std::to_string(kTraceTile) + "\n";
  if (kind == kBakedProgram) fragment += "#define TRACE_TILE_START 1\n";
  if (kind == kBakedTileProgram) fragment += "#define TRACE_TILE_PASS 1\n";
  fragment += shaderSource(file);
  // The baked trace pass draws rectangles of pixels (tile_spans.h); the others one triangle.
  const char* vertex = kind == kBakedProgram ? "pixel_rects.vert" : "fullscreen.vert";
  return buildProgram({ShaderSource{GL_VERTEX_SHADER, std::string(shaderSource(vertex)), vertex},
                       ShaderSource{GL_FRAGMENT_SHADER, fragment, file}});
}

// Rounding of a float sum errs by about 2⁻²⁴·√N·Σ|terms| (random-walk growth over N terms; the
// terms' own rounding is of the same order). HRBF and RBF-offset fits have |∇f| ≈ 1 at the data,
// so that error moves the surface by about as much in world units: above 1e-4 of the diagonal
// (the exact march's ε) use double. RBF-offset dipoles and polyharmonic kernels over wide
// bounds get there (Σ|terms| of 10⁵–10⁶ against f ≈ 1, where float draws false surfaces).
bool floatEvaluationTooCoarse(const RadialSum<3>& model, const Box<3>& bounds) {
  constexpr int kProbes = 6;
  double terms = 0.0;
  for (int k = 0; k < kProbes; ++k)
    for (int j = 0; j < kProbes; ++j)
      for (int i = 0; i < kProbes; ++i) {
        const Vec<3> u = (Vec<3>(i, j, k).array() + 0.5) / double(kProbes);
        terms = std::max(terms, model.termMagnitude(bounds.lo + bounds.extent().cwiseProduct(u)));
      }
  const double n = double(std::max<Eigen::Index>(model.centres().cols(), 1));
  const double floatError = std::ldexp(1.0, -24) * std::sqrt(n) * terms;
  return floatError > 1e-4 * bounds.extent().norm();
}

// max |f| of the baked interpolant on the slice plane inside the bounds (64² probes).
double sliceRangeFromBake(const VolumeBake& bake, const Vec<3>& n, double offset) {
  Vec<3> u, v;
  planeBasis(n, u, v);
  const Vec<3> c = bake.bounds.center();
  const Vec<3> c0 = c + (offset - n.dot(c)) * n;
  const double half = 0.5 * bake.bounds.extent().norm();
  double range = 0;
  const int m = 64;
  for (int a = 0; a <= m; ++a)
    for (int b = 0; b <= m; ++b) {
      const Vec<3> x = c0 + (-half + 2 * half * a / m) * u + (-half + 2 * half * b / m) * v;
      if (!bake.bounds.contains(x)) continue;
      range = std::max(range, std::abs(bake.interpolate(x)));
    }
  return range > 0 && std::isfinite(range) ? range : 1.0;
}

// The cone about a tile's centre ray that holds all of the tile's pixel rays: radius
// radius0 + slope·a at axial distance a (trace_tile_pass.glsl), and reach ≥ that radius anywhere
// inside the bounds. Pixel centres lie within (tile − 1)/2 pixels of the tile's centre per axis.
struct TileCone {
  double slope = 0, radius0 = 0, reach = 0;
};

TileCone tileCone(const Camera& camera, const Box<3>& bounds, int tile) {
  const double offsetPixels = 0.5 * (tile - 1) * std::sqrt(2.0);
  TileCone cone;
  if (camera.projection() == Projection::Orthographic) {
    cone.radius0 = offsetPixels * 2.0 * camera.halfHeight() / camera.height();
  } else {
    // Directions c + e with |c| ≥ 1 (the forward axis has length 1) and |e| ≤ δ at unit distance:
    // the angle φ between them has tan φ ≤ δ / (1 − δ).
    const double delta = offsetPixels * 2.0 * camera.tanHalfFov() / camera.height();
    cone.slope = delta / (1.0 - delta);
  }
  // 1 % slack for the shader's float arithmetic.
  cone.slope *= 1.01;
  cone.radius0 *= 1.01;
  cone.reach = 1.01 * (cone.radius0 + cone.slope * bounds.farthestDistance(camera.eye())) + 1e-6 * bounds.extent().norm();
  return cone;
}

// One render's view of the scene, shared by its passes.
struct TraceFrame {
  const Camera& camera;
  const TraceSettings& settings;
  Box<3> bounds;
  int width = 0, height = 0;
  Eigen::Matrix4d viewProjection;  // projection · view, with the tracer's depth range as [near, far]
  glm::mat4 viewProj;              // the same in float, for the shaders
  Vec<3> sliceNormal;              // unit when the slice is enabled
  double sliceRange = 1;           // |f| at the ends of the slice's heat map
  double minStep = 0;              // ε of the march in world units
  std::array<std::uint8_t, 3> background{};  // round(255·c) of settings.background

  // Throws InputError for a zero or non-finite slice normal.
  TraceFrame(const Camera& view, const TraceSettings& traceSettings, const Box<3>& box, const VolumeBake& bake,
             const Eigen::Vector2d& depthRange);

  std::size_t pixels() const { return std::size_t(width) * height; }
  // Where the ray meets the slice plane inside the bounds; +inf where it does not, or without a slice.
  double planeT(const Ray& ray) const;
  // The window depth of a world point, as the trace pass writes it.
  float windowDepth(const Vec<3>& x) const {
    const Eigen::Vector4d clip = viewProjection * Eigen::Vector4d(x.x(), x.y(), x.z(), 1.0);
    return float(std::clamp(0.5 * clip.z() / clip.w() + 0.5, 0.0, 1.0));
  }
};

TraceFrame::TraceFrame(const Camera& view, const TraceSettings& traceSettings, const Box<3>& box,
                       const VolumeBake& bake, const Eigen::Vector2d& depthRange)
    : camera(view), settings(traceSettings), bounds(box), width(view.width()), height(view.height()) {
  const SliceSettings& slice = settings.slice;
  sliceNormal = Vec<3>(slice.normal[0], slice.normal[1], slice.normal[2]);
  if (slice.enabled) {
    if (!(sliceNormal.norm() > 0) || !sliceNormal.allFinite())
      throw InputError("view.slice.normal: must be a non-zero vector");
    sliceNormal.normalize();
    sliceRange = slice.range > 0 ? slice.range : sliceRangeFromBake(bake, sliceNormal, slice.offset);
  }
  viewProjection = view.projectionMatrix(depthRange(0), depthRange(1)) * view.viewMatrix();
  viewProj = toGlm(viewProjection);
  minStep = settings.mode == TracerMode::Baked ? settings.minStepCells * bake.spacing().minCoeff()
                                               : settings.minStepCells * 1e-3 * bounds.extent().norm();
  for (int k = 0; k < 3; ++k) background[k] = shading::toByte(settings.background[k]);
}

double TraceFrame::planeT(const Ray& ray) const {
  if (!settings.slice.enabled) return std::numeric_limits<double>::infinity();
  const double dn = ray.direction.dot(sliceNormal);
  double a, b;
  if (dn == 0 || !clipRayToBox(ray, bounds, a, b)) return std::numeric_limits<double>::infinity();
  const double tp = (settings.slice.offset - sliceNormal.dot(ray.origin)) / dn;
  return (tp >= a && tp <= b) ? tp : std::numeric_limits<double>::infinity();
}

// The uniforms every trace program takes: camera, bounds and bricks, the march, shading and the
// slice plane.
void setTraceUniforms(const Program& p, const TraceFrame& frame, const VolumeBake& bake) {
  const Camera& camera = frame.camera;
  const TraceSettings& settings = frame.settings;
  p.setUniform("uViewport", glm::vec2(float(camera.width()), float(camera.height())));
  p.setUniform("uEye", toGlm(camera.eye()));
  p.setUniform("uRight", toGlm(camera.right()));
  p.setUniform("uUp", toGlm(camera.up()));
  p.setUniform("uForward", toGlm(camera.forward()));
  p.setUniform("uTileSize", 1.0f);
  p.setUniform("uTanHalf", float(camera.tanHalfFov()));
  p.setUniform("uAspect", float(camera.aspect()));
  p.setUniform("uHalfHeight", float(camera.halfHeight()));
  p.setUniform("uOrtho", camera.projection() == Projection::Orthographic ? 1 : 0);
  p.setUniform("uViewProj", frame.viewProj);
  p.setUniform("uBoundsLo", toGlm(frame.bounds.lo));
  p.setUniform("uBoundsHi", toGlm(frame.bounds.hi));
  p.setUniform("uBrickCount", glm::ivec3(bake.bricks.count.x(), bake.bricks.count.y(), bake.bricks.count.z()));
  p.setUniform("uBrickSize", toGlm(bake.bricks.size));
  p.setUniform("uMinStep", float(frame.minStep));
  p.setUniform("uMaxSteps", 4096);
  p.setUniform("uLoopBudget", 1 << 30);  // exact mode on a software renderer sets its own
  p.setUniform("uShowSurface", settings.showSurface ? 1 : 0);
  p.setUniform("uBackground", glm::vec3(frame.background[0] / 255.0f, frame.background[1] / 255.0f,
                                        frame.background[2] / 255.0f));
  p.setUniform("uFrontColor", toGlm(shading::kFrontColor));
  p.setUniform("uBackColor", toGlm(shading::kBackColor));
  p.setUniform("uAmbient", float(shading::kAmbient));
  for (int k = 0; k < 2; ++k) {
    const shading::Light& l = shading::kLights[k];
    const Vec<3> dir = shading::lightDirection(l, camera.right(), camera.up(), camera.forward());
    p.setUniform("uLightDir[" + std::to_string(k) + "]", toGlm(dir));
    p.setUniform("uLightIntensity[" + std::to_string(k) + "]", float(l.intensity));
  }
  const SliceSettings& s = settings.slice;
  p.setUniform("uSliceEnabled", s.enabled ? 1 : 0);
  if (s.enabled) {
    p.setUniform("uSliceNormal", toGlm(frame.sliceNormal));
    p.setUniform("uSliceOffset", float(s.offset));
    p.setUniform("uSliceRange", float(frame.sliceRange));
    p.setUniform("uIsoSpacing", float(niceIsoSpacing(frame.sliceRange)));
    p.setUniform("uZeroColor", glm::vec3(float(kZeroCurveColor[0]), float(kZeroCurveColor[1]), float(kZeroCurveColor[2])));
    p.setUniform("uIsoDarken", float(kIsoLineDarken));
  }
}

// The loop budget of the exact march on a software rasteriser (uLoopBudget in trace_common.glsl):
// Mesa's loop limit less the evaluations after the march (∇f at the hit, the slice's f and ∇f)
// and the small fixed loops. Pixels that run out are traced on the CPU; a model too big for even
// one step is refused (InputError).
int exactLoopBudget(int paddedCentres, Eigen::Index centres) {
  const int perEvaluation = paddedCentres / 4;
  const int budget = kMesaSoftwareLoopLimit - 3 * perEvaluation - 256;
  if (budget < 4 * perEvaluation)
    throw InputError("implicit tracer: exact mode on this software renderer (Mesa llvmpipe) handles at most " +
                     std::to_string((kMesaSoftwareLoopLimit - 256) / 7 * 4) + " centres (the model has " +
                     std::to_string(centres) + "); use the baked mode");
  return budget;
}

// The trace pass's hit texture as read back: RGBA32F per pixel (t, GPU normal), GL rows bottom-up.
std::vector<float> readHitTexture(const TraceTarget& target) {
  return readTexture<float>(target.hit, GL_RGBA, GL_FLOAT, 4);
}

// The hits of `hitData` (readHitTexture of a W × H target; row 0 = top from here on): the result
// gets each hit's depth and the GPU's normal. Returns the surface's ray parameter per pixel:
// ≥ 0 a hit, −1 a miss, −2 where the march ran out of steps or loop budget (undecided).
std::vector<float> surfaceHits(const std::vector<float>& hitData, int W, int H, TraceResult& result) {
  const std::size_t npx = std::size_t(W) * H;
  result.hit.assign(npx, 0);
  result.depth.assign(npx, std::numeric_limits<float>::infinity());
  result.normal.assign(3 * npx, 0.0f);
  std::vector<float> surfaceT(npx, -1.0f);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const float* h = &hitData[4 * (std::size_t(H - 1 - j) * W + i)];
      const std::size_t p = std::size_t(j) * W + i;
      surfaceT[p] = h[0];
      if (h[0] >= 0) {
        result.depth[p] = h[0];
        for (int k = 0; k < 3; ++k) result.normal[3 * p + k] = h[1 + k];
      }
    }
  return surfaceT;
}

std::vector<float> readSurfaceHits(const TraceTarget& target, TraceResult& result) {
  return surfaceHits(readHitTexture(target), target.width, target.height, result);
}

std::vector<int> undecidedPixels(const std::vector<float>& surfaceT) {
  std::vector<int> undecided;
  for (std::size_t p = 0; p < surfaceT.size(); ++p)
    if (surfaceT[p] < -1.5f) undecided.push_back(int(p));
  return undecided;
}

// Without refinement the GPU's surface hit is the visible one unless the slice plane is nearer;
// where the plane wins, the result records no surface there.
void keepVisibleSurface(const TraceFrame& frame, const std::vector<float>& surfaceT, TraceResult& result) {
  if (!frame.settings.slice.enabled) {  // no plane (planeT is +∞): every hit is visible
    for (std::size_t p = 0; p < surfaceT.size(); ++p)
      if (surfaceT[p] >= 0) result.hit[p] = 1;
    return;
  }
  for (int j = 0; j < frame.height; ++j)
    for (int i = 0; i < frame.width; ++i) {
      const std::size_t p = std::size_t(j) * frame.width + i;
      if (surfaceT[p] < 0) continue;
      const double tp = frame.planeT(frame.camera.pixelRay(i, j));
      if (double(surfaceT[p]) < tp) {
        result.hit[p] = 1;
      } else {
        result.depth[p] = std::numeric_limits<float>::infinity();
        for (int k = 0; k < 3; ++k) result.normal[3 * p + k] = 0.0f;
      }
    }
}

// Shades a visible refined hit exactly like core/trace/shading.h, with the true field's normal,
// into the pixel's colour bytes and the result; returns its window depth.
float shadeRefinedHit(const TraceFrame& frame, const Ray& ray, double t, const Vec<3>& g, std::uint8_t* px,
                      TraceResult& result, std::size_t p) {
  const Camera& camera = frame.camera;
  const double gn = g.norm();
  const Vec<3> n = (gn > 0 && std::isfinite(gn)) ? Vec<3>(g / gn) : Vec<3>(-ray.direction);
  const Vec<3> c = shading::shadeHit(n, ray.direction, camera.right(), camera.up(), camera.forward());
  for (int k = 0; k < 3; ++k) px[k] = shading::toByte(c(k));
  px[3] = 255;
  result.hit[p] = 1;
  result.depth[p] = float(t);
  for (int k = 0; k < 3; ++k) result.normal[3 * p + k] = float(n(k));
  return frame.windowDepth(ray.at(t));
}

// Composites the refined surface with the slice plane and the background on the CPU (the nearer
// of surface and plane wins) wherever the GPU or the refinement found a surface, into the trace
// pass's colour and depth (GL rows bottom-up), so that the overlays are depth-tested against the
// refined surface. Returns the pixels that show a refined hit.
// Rows [rowBegin, rowEnd) (row 0 = top; rowEnd < 0: every row), each pixel on its own.
int compositeRefinedPixels(const TraceFrame& frame, const HitRefinement& hits, const std::vector<std::uint8_t>& planeColor,
                           std::vector<std::uint8_t>& color, std::vector<float>& depth, TraceResult& result,
                           int rowBegin = 0, int rowEnd = -1) {
  const int W = frame.width, H = frame.height;
  const int j1 = rowEnd < 0 ? H : std::min(rowEnd, H);
  int refined = 0;
#pragma omp parallel for schedule(static) reduction(+ : refined)
  for (int j = rowBegin; j < j1; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t p = std::size_t(j) * W + i;
      const std::size_t glIndex = std::size_t(H - 1 - j) * W + i;
      if (!hits.gpuHit[p] && hits.t[p] < 0) continue;  // GPU colour (background or plane) stands
      const Ray ray = frame.camera.pixelRay(i, j);
      const double tp = frame.planeT(ray);
      std::uint8_t* px = &color[4 * glIndex];
      result.hit[p] = 0;
      result.depth[p] = std::numeric_limits<float>::infinity();
      for (int k = 0; k < 3; ++k) result.normal[3 * p + k] = 0.0f;
      if (hits.t[p] >= 0 && hits.t[p] < tp) {
        ++refined;
        depth[glIndex] = shadeRefinedHit(frame, ray, hits.t[p], hits.gradient[p], px, result, p);
      } else if (std::isfinite(tp) && planeColor[4 * glIndex + 3] > 0) {
        std::memcpy(px, &planeColor[4 * glIndex], 3);
        px[3] = 255;
        depth[glIndex] = frame.windowDepth(ray.at(tp));
      } else {
        std::memcpy(px, frame.background.data(), 3);
        px[3] = 255;
        depth[glIndex] = 1.0f;
      }
    }
  return refined;
}

// The trace pass's colour, plane colour and depth, GL rows bottom-up.
struct TracePassPixels {
  std::vector<std::uint8_t> color, planeColor;
  std::vector<float> depth;
};

TracePassPixels readTracePass(const TraceTarget& target) {
  return {readTexture<std::uint8_t>(target.color, GL_RGBA, GL_UNSIGNED_BYTE, 4),
          readTexture<std::uint8_t>(target.plane, GL_RGBA, GL_UNSIGNED_BYTE, 4),
          readTexture<float>(target.depth, GL_DEPTH_COMPONENT, GL_FLOAT, 1)};
}

// Writes composited colour and depth (GL rows bottom-up) back to the target.
void writeTracePass(const TraceTarget& target, const std::vector<std::uint8_t>& color, const std::vector<float>& depth) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(target.color.id(), 0, 0, 0, target.width, target.height, GL_RGBA, GL_UNSIGNED_BYTE, color.data());
  glTextureSubImage2D(target.depth.id(), 0, 0, 0, target.width, target.height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  checkGl("implicit tracer refinement upload");
}

// The refinement options of a frame's settings over a bake.
HitRefinementOptions refinementOptions(const TraceSettings& settings, const VolumeBake& bake, const CancelToken* cancel) {
  HitRefinementOptions options;
  options.refine = settings.refineExact;
  options.cell = bake.spacing().norm();
  options.cpuMinStep = settings.minStepCells * 1e-3;  // the exact march's ε, relative to the diagonal
  options.bake = &bake;
  options.cancel = cancel;
  return options;
}

}  // namespace

struct ImplicitTracer::Gpu {
  // [TraceProgramKind][slice][no data], built on first use
  std::unique_ptr<Program> programs[kTraceProgramKinds][2][2];
  VertexArray empty;
  Buffer rectVertices;  // the baked trace pass's rectangles: (x, y) pixel corners, 2 triangles each
  GLsizei rectVertexCount = 0;
  VertexArray rects;
  Texture volume;
  Texture normals;      // baked mode: RGBA8 unit directions per sample (baked_normals.h)
  Texture bricks;
  Texture bakedBricks;  // baked mode: per fine brick (L of the interpolant, brick distance, L around, unused)
  Eigen::Array3i bakedBrickCount = Eigen::Array3i::Zero();
  Vec<3> bakedBrickSize = Vec<3>::Zero();
  Buffer centres;        // exact mode: vec4 (c − origin, α) per centre
  Buffer betas;          // vec4 (β, 0)
  Buffer centresDouble;  // the same in dvec4, for the double program
  Buffer betasDouble;
  std::unique_ptr<TraceTarget> target;
  std::unique_ptr<OverlayRenderer> overlay;
  std::array<double, 10> shiftedPoly{};
  Vec<3> origin = Vec<3>::Zero();
  int paddedCentres = 0;  // centres in the SSBOs: N rounded up to a multiple of 4 (α = β = 0 pads)
  double sampleSpacing = 0;  // mean nearest-neighbour distance of the uploaded samples (0: none)
  bool softwareLoopLimit = isMesaSoftwareRenderer();

  const Program& program(TraceProgramKind kind, bool slice, bool noData = false) {
    std::unique_ptr<Program>& slot = programs[kind][slice ? 1 : 0][noData ? 1 : 0];
    if (!slot) slot = std::make_unique<Program>(buildTraceProgram(kind, slice, noData));
    return *slot;
  }
  TraceTarget& targetFor(int width, int height) {
    if (!target || target->width != width || target->height != height)
      target = std::make_unique<TraceTarget>(width, height);
    return *target;
  }
  void uploadModel(const RadialSum<3>& model, const Vec<3>& centre);
  long long prepareTrace(const TraceFrame& frame, const VolumeBake& bake, int tileRows);
  // The tile pass's tile rows the trace needs: the tile target's height in baked mode with the
  // surface shown, else none.
  int tilePassRows(const TraceFrame& frame) const {
    return frame.settings.mode == TracerMode::Baked && frame.settings.showSurface ? target->tileHeight : 0;
  }
  void setTraceState();
  void traceRows(const TraceFrame& frame, const VolumeBake& bake, const RadialSum<3>* model, bool exactDouble, int y0,
                 int y1);
  void runTilePass(const TraceFrame& frame, const VolumeBake& bake, int row0, int row1);
  void bindBaked(const Program& p, const TraceFrame& frame, const VolumeBake& bake);
  void bindExact(const Program& p, const RadialSum<3>& model, bool exactDouble, int loopBudget);
  long long prepareRects(const TraceFrame& frame);
  ImageRgba8 drawOverlays(const TraceFrame& frame, const HermiteSamples<3>* samples);
  // The overlays into the target's colour, depth-tested; the caller's scissor limits the rows.
  void drawOverlayContent(const TraceFrame& frame, const HermiteSamples<3>* samples);
  void scaleMarksToSpacing(const TraceFrame& frame, OverlayContent& content) const;
};

namespace {

// The caller's framebuffer bindings and viewport, put back when it goes out of scope: a frame
// traced in bands returns to the caller between them (the window then draws its panels into
// its own framebuffer, not into the trace target).
class KeepFramebuffer {
 public:
  KeepFramebuffer() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
  }
  ~KeepFramebuffer() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  }
  KeepFramebuffer(const KeepFramebuffer&) = delete;
  KeepFramebuffer& operator=(const KeepFramebuffer&) = delete;

 private:
  GLint draw_ = 0, read_ = 0;
  GLint viewport_[4] = {};
};

// Limits drawing to GL rows [row0, row1) of a target `width` × `height` while in scope (a band of
// the trace pass, a part of the tile pass, refined rows); no scissor when the rows are all of them.
class RowScissor {
 public:
  RowScissor(int width, int height, int row0, int row1) : on_(row0 > 0 || row1 < height) {
    if (!on_) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, row0, width, row1 - row0);
  }
  ~RowScissor() {
    if (on_) glDisable(GL_SCISSOR_TEST);
  }
  RowScissor(const RowScissor&) = delete;
  RowScissor& operator=(const RowScissor&) = delete;

 private:
  bool on_;
};

}  // namespace

// A frame traced over several calls: copies of what its passes read (TraceFrame refers to them)
// and how far the trace pass got.
struct ImplicitTracer::Frame {
  Camera camera;
  TraceSettings settings;
  std::optional<TraceFrame> frame;
  TraceResult result;  // sliceRange, exactDouble, tracedPixels and traceMs so far
  int nextRow = 0;     // GL rows [0, nextRow) are traced
  int tileRows = 0;    // rows of the tile target the tile pass ran on (all: Gpu::tilePassRows)
  double maxMsPerRow = 0;  // the costliest band's ms per row so far, for the next band's height
  // What readBackStep read and converted so far, for finishFrame.
  std::optional<std::vector<float>> hitData;  // readHitTexture, until converted into surfaceT
  std::optional<std::vector<float>> surfaceT;
  std::optional<std::vector<int>> undecided;
  std::optional<TracePassPixels> pass;
  Frame(const Camera& c, const TraceSettings& s) : camera(c), settings(s) {}
};

// An upload in progress: its textures and what the tracer takes with them.
struct ImplicitTracer::Staged {
  StagedVolumeUpload upload;
  const ImplicitField<3>* field = nullptr;
  HermiteSamples<3> samples;
  bool hasSamples = false;
  explicit Staged(TracerVolume v) : upload(std::move(v)) {}
};

ImplicitTracer::ImplicitTracer() : gpu_(std::make_unique<Gpu>()) {
  gpu_->program(kBakedProgram, false);
  gpu_->rects.setVertexBuffer(0, gpu_->rectVertices, 0, 2 * sizeof(float));
  gpu_->rects.setAttribute(0, 0, 2, GL_FLOAT, false, 0);
  gpu_->overlay = std::make_unique<OverlayRenderer>();
}

ImplicitTracer::~ImplicitTracer() = default;

bool ImplicitTracer::hasExactModel() const { return radialSum_ != nullptr; }

bool ImplicitTracer::exactNeedsDouble() const {
  if (!exactNeedsDouble_) exactNeedsDouble_ = radialSum_ != nullptr && floatEvaluationTooCoarse(*radialSum_, bounds_);
  return *exactNeedsDouble_;
}

const VolumeBake& ImplicitTracer::bake() const {
  if (!bake_) throw InputError("implicit tracer: nothing uploaded");
  return *bake_;
}

Eigen::Vector2d ImplicitTracer::depthRange(const Camera& camera) const {
  Box<3> grown = bounds_;
  const double pad = 0.1 * bounds_.extent().norm();
  grown.lo.array() -= pad;
  grown.hi.array() += pad;
  return camera.depthRange(grown);
}

TracerVolume prepareTracerVolume(const ImplicitField<3>& field, const Box<3>& bounds,
                                 const TracerUploadOptions& options, const CancelToken* cancel) {
  const auto t0 = Clock::now();
  VolumeBakeOptions bakeOptions;
  bakeOptions.resolution = options.bakeResolution;
  bakeOptions.brickCells = options.brickCells;
  bakeOptions.cancel = cancel;
  TracerVolume v;
  auto bake = std::make_shared<VolumeBake>(bakeVolume(field, bounds, bakeOptions));
  v.brickTexels = brickTexels(*bake);
  throwIfCancelled(cancel);
  BakedBricks baked = bakedBrickTexels(*bake, kBakedBrickCells);
  v.bakedBrickTexels = std::move(baked.texels);
  v.bakedBrickCount = baked.count;
  v.bakedBrickSize = baked.size;
  throwIfCancelled(cancel);
  v.normalTexels = bakedNormalTexels(*bake);
  v.bake = std::move(bake);
  v.bakeMs = msSince(t0);
  return v;
}

void ImplicitTracer::upload(const ImplicitField<3>& field, const Box<3>& bounds, const HermiteSamples<3>* samples,
                            const TracerUploadOptions& options) {
  upload(prepareTracerVolume(field, bounds, options), field, samples);
}

void ImplicitTracer::upload(TracerVolume volume, const ImplicitField<3>& field, const HermiteSamples<3>* samples) {
  const auto t0 = Clock::now();
  beginUpload(std::move(volume), field, samples);
  continueUpload(std::numeric_limits<double>::infinity());
  glFinish();
  checkGl("implicit tracer upload");
  uploadMs_ = msSince(t0);
}

void ImplicitTracer::beginUpload(TracerVolume volume, const ImplicitField<3>& field, const HermiteSamples<3>* samples) {
  staged_.reset();
  auto staged = std::make_unique<Staged>(std::move(volume));
  staged->field = &field;
  staged->hasSamples = samples != nullptr && samples->size() > 0;
  if (staged->hasSamples) staged->samples = *samples;
  staged_ = std::move(staged);
}

bool ImplicitTracer::continueUpload(double budgetMs) {
  if (!staged_) return true;
  try {
    if (!staged_->upload.copy(budgetMs)) return false;
  } catch (...) {
    staged_.reset();  // the previous upload stays
    throw;
  }
  adoptStaged();
  return true;
}

// The finished upload becomes the tracer's: its textures, field, model and samples.
void ImplicitTracer::adoptStaged() {
  const std::unique_ptr<Staged> staged = std::move(staged_);
  frame_.reset();  // a frame in progress traces the old bake
  TracerVolume& volume = staged->upload.volume();
  VolumeTextures& t = staged->upload.textures();
  bakeMs_ = volume.bakeMs;
  uploadMs_ = staged->upload.copyMs();
  gpu_->volume = std::move(t.volume);
  gpu_->normals = std::move(t.normals);
  gpu_->bricks = std::move(t.bricks);
  gpu_->bakedBricks = std::move(t.bakedBricks);
  gpu_->bakedBrickCount = volume.bakedBrickCount;
  gpu_->bakedBrickSize = volume.bakedBrickSize;
  field_ = staged->field;
  radialSum_ = field_->asRadialSum();
  bounds_ = volume.bake->bounds;
  exactNeedsDouble_.reset();
  if (radialSum_) gpu_->uploadModel(*radialSum_, bounds_.center());
  hasSamples_ = staged->hasSamples;
  if (hasSamples_) samples_ = std::move(staged->samples);
  gpu_->sampleSpacing = !hasSamples_               ? 0.0
                        : volume.sampleSpacing >= 0 ? volume.sampleSpacing
                                                    : meanSampleSpacing<3>(samples_.points);
  bake_ = std::move(volume.bake);
  checkGl("implicit tracer upload");
}

// Uploads a RadialSum's centres (relative to `centre`, which keeps float sums accurate) with α
// and β to the exact mode's SSBOs in float and in double (both programs may run), and its
// polynomial re-expressed about that centre.
void ImplicitTracer::Gpu::uploadModel(const RadialSum<3>& model, const Vec<3>& centre) {
  origin = centre;
  const int n = int(model.centres().cols());
  paddedCentres = std::max(4, (n + 3) / 4 * 4);  // the shader takes 4 centres per loop iteration
  const std::size_t slots = 4 * std::size_t(paddedCentres);
  std::vector<double> ca(slots, 0.0), beta(slots, 0.0);
  for (int j = 0; j < n; ++j) {
    const Vec<3> c = model.centres().col(j) - origin;
    for (int k = 0; k < 3; ++k) ca[4 * j + k] = c(k);
    ca[4 * j + 3] = model.alpha()(j);
    if (model.hasBeta())
      for (int k = 0; k < 3; ++k) beta[4 * j + k] = model.beta()(k, j);
  }
  const std::vector<float> caFloat(ca.begin(), ca.end()), betaFloat(beta.begin(), beta.end());
  centres.setData(caFloat.data(), caFloat.size() * sizeof(float), GL_STATIC_DRAW);
  betas.setData(betaFloat.data(), betaFloat.size() * sizeof(float), GL_STATIC_DRAW);
  centresDouble.setData(ca.data(), ca.size() * sizeof(double), GL_STATIC_DRAW);
  betasDouble.setData(beta.data(), beta.size() * sizeof(double), GL_STATIC_DRAW);
  shiftedPoly = shiftPolynomial(model.polynomial(), model.poly(), origin - model.polyOrigin());
}

// The GPU trace pass in two steps. prepareTrace runs the tile pass and sets up which pixels the
// trace pass runs on (baked mode); traceRows marches the rays of GL rows [y0, y1) (the bake in
// baked mode, the model's sum in exact mode) and writes colour, hit data (t and normal), the slice
// plane's colour and depth to the target. A whole frame is one traceRows over every row, without
// a scissor; the window's settled frames trace bands of rows over several GUI frames, which give
// the same bytes (each pixel's ray is independent of the others). Returns the pixels traced.
// `tileRows`: the tile pass runs on tile rows [0, tileRows) now, the rest later (runTilePass).
long long ImplicitTracer::Gpu::prepareTrace(const TraceFrame& frame, const VolumeBake& bake, int tileRows) {
  const TraceSettings& settings = frame.settings;
  setTraceState();
  if (settings.mode != TracerMode::Baked) return (long long)frame.pixels();
  if (tileRows > 0) runTilePass(frame, bake, 0, tileRows);
  return -1;  // the rectangles are left to prepareRects
}

// The pipeline state of the trace pass: the target with all its buffers, no blending, depth
// written as the shader computes it.
void ImplicitTracer::Gpu::setTraceState() {
  target->bind();
  target->setAllBuffers();
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
}

void ImplicitTracer::Gpu::traceRows(const TraceFrame& frame, const VolumeBake& bake, const RadialSum<3>* model,
                                    bool exactDouble, int y0, int y1) {
  const TraceSettings& settings = frame.settings;
  const bool baked = settings.mode == TracerMode::Baked;
  setTraceState();
  const int loopBudget =
      !baked && softwareLoopLimit ? exactLoopBudget(paddedCentres, model->centres().cols()) : 1 << 30;
  const TraceProgramKind kind = baked ? kBakedProgram : exactDouble ? kExactDoubleProgram : kExactFloatProgram;
  const Program& p = program(kind, settings.slice.enabled, baked && !bake.noData.empty());
  p.use();
  setTraceUniforms(p, frame, bake);
  if (baked) {
    bindBaked(p, frame, bake);
    target->tileStart.bind(3);
    p.setUniform("uTileStart", 3);
  } else {
    bindExact(p, *model, exactDouble, loopBudget);
  }
  bricks.bind(1);
  p.setUniform("uBricks", 1);
  {
    const RowScissor band(frame.width, frame.height, y0, y1);
    if (baked) {
      rects.bind();
      if (rectVertexCount > 0) glDrawArrays(GL_TRIANGLES, 0, rectVertexCount);
    } else {
      empty.bind();
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glFinish();
  checkGl("implicit tracer trace pass");
}

// The baked mode's tile pass: per tile of kTraceTile² pixels, how far along its rays the trace
// pass may skip (trace_tile_pass.glsl), from the march of a cone that holds all the tile's rays;
// on tile rows [row0, row1) (GL rows of the tile target: a part of the pass under a scissor).
void ImplicitTracer::Gpu::runTilePass(const TraceFrame& frame, const VolumeBake& bake, int row0, int row1) {
  const Program& tiles = program(kBakedTileProgram, false);
  tiles.use();
  setTraceUniforms(tiles, frame, bake);
  bindBaked(tiles, frame, bake);
  const TileCone cone = tileCone(frame.camera, frame.bounds, kTraceTile);
  tiles.setUniform("uTileSize", float(kTraceTile));
  tiles.setUniform("uConeSlope", float(cone.slope));
  tiles.setUniform("uConeRadius0", float(cone.radius0));
  tiles.setUniform("uConeReach", float(cone.reach));
  target->bindTiles();
  empty.bind();
  glDisable(GL_DEPTH_TEST);
  {
    const RowScissor part(target->tileWidth, target->tileHeight, row0, row1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glEnable(GL_DEPTH_TEST);
  target->bind();
}

// Binds the baked mode's textures: the bake, its normals and the baked mode's own, finer brick
// grid, which the baked march steps over.
void ImplicitTracer::Gpu::bindBaked(const Program& p, const TraceFrame& frame, const VolumeBake& bake) {
  volume.bind(0);
  p.setUniform("uVolume", 0);
  const Vec<3> scale = Vec<3>::Constant(bake.resolution - 1).cwiseQuotient(frame.bounds.extent());
  p.setUniform("uVolumeScale", toGlm(scale));
  p.setUniform("uVolumeResolution", float(bake.resolution));
  p.setUniform("uCell", toGlm(bake.spacing()));
  p.setUniform("uBrickCount", glm::ivec3(bakedBrickCount.x(), bakedBrickCount.y(), bakedBrickCount.z()));
  p.setUniform("uBrickSize", toGlm(bakedBrickSize));
  bakedBricks.bind(2);
  p.setUniform("uBakedBricks", 2);
  normals.bind(4);
  p.setUniform("uNormals", 4);
}

// Binds the exact mode's model: centres and β from the SSBOs of the program's precision, kernel,
// polynomial (`real` uniforms in that precision) and the loop budget.
void ImplicitTracer::Gpu::bindExact(const Program& p, const RadialSum<3>& model, bool exactDouble, int loopBudget) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, (exactDouble ? centresDouble : centres).id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, (exactDouble ? betasDouble : betas).id());
  p.setUniform("uCount", paddedCentres);
  p.setUniform("uLoopBudget", loopBudget);
  p.setUniform("uHasBeta", model.hasBeta() ? 1 : 0);
  p.setUniform("uKernel", kernelInfo(model.kernel().type).id);
  p.setUniform("uPolyCount", monomialCount<3>(model.polynomial()));
  auto setReal = [&](const std::string& name, double v) {
    if (exactDouble)
      p.setUniform(name, v);
    else
      p.setUniform(name, float(v));
  };
  setReal("uRadius", model.kernel().radius);
  for (int k = 0; k < 10; ++k) setReal("uPoly[" + std::to_string(k) + "]", shiftedPoly[k]);
  p.setUniform("uOrigin", toGlm(origin));
}

// The rectangles the baked trace program draws: without a slice plane only the tiles the tile
// pass did not prove empty (tile_spans.h), the others cleared to what a miss writes; the slice
// plane can cover any pixel, so with it every pixel runs. Returns the pixels they cover.
long long ImplicitTracer::Gpu::prepareRects(const TraceFrame& frame) {
  const TraceSettings& settings = frame.settings;
  std::vector<PixelRect> rectList{PixelRect{0, 0, frame.width, frame.height}};
  if (settings.showSurface && !settings.slice.enabled && settings.skipEmptyTiles) {
    const std::vector<float> tiles = readTexture<float>(target->tileStart, GL_RED, GL_FLOAT, 1);
    rectList = occupiedTileRects(tiles, target->tileWidth, target->tileHeight, kTraceTile, frame.width, frame.height);
  }
  const long long traced = rectPixels(rectList);
  if (traced < (long long)frame.pixels()) target->clearToMiss(settings.background);
  const std::vector<float> corners = rectTriangles(rectList);
  rectVertices.setData(std::span<const float>(corners));  // same buffer id: the binding stands
  rectVertexCount = GLsizei(corners.size() / 2);
  return traced;
}

// Points and normals scaled to the mean sample spacing s, so that a dense cloud is not a hairball
// of normals over a carpet of dots: normals at most kNormalSpacings·s long (else 5 % of the
// bounds diagonal, the length sparse clouds keep), dots at most kDotSpacings·s wide at the
// camera's target distance, between 2 and 4 px, and none while s is under kMinDotGapPx there: 2 px
// dots would cover the surface (a 100 000-point scan in full view has about one sample a pixel).
void ImplicitTracer::Gpu::scaleMarksToSpacing(const TraceFrame& frame, OverlayContent& content) const {
  constexpr double kNormalSpacings = 2.0, kDotSpacings = 0.5;
  const double diagonal = frame.bounds.extent().norm();
  if (!(sampleSpacing > 0) || !(diagonal > 0)) return;
  content.normalLength = std::min(content.normalLength, kNormalSpacings * sampleSpacing / diagonal);
  const Camera& c = frame.camera;
  // World units per pixel at the bounds' centre.
  const double depth = std::max((frame.bounds.center() - c.eye()).dot(c.forward()), 1e-12);
  const double unitsPerPx = c.projection() == Projection::Orthographic ? 2 * c.halfHeight() / c.height()
                                                                        : 2 * depth * c.tanHalfFov() / c.height();
  const double spacingPx = sampleSpacing / unitsPerPx;
  if (spacingPx < kMinDotGapPx) content.showPoints = false;
  content.pointSize = float(std::clamp(kDotSpacings * spacingPx, 2.0, double(content.pointSize)));
}

// Draws the overlays (points, normals, bounds box) depth-tested against the traced depth, and
// reads the final colour back, flipped so that row 0 = top.
ImageRgba8 ImplicitTracer::Gpu::drawOverlays(const TraceFrame& frame, const HermiteSamples<3>* samples) {
  drawOverlayContent(frame, samples);
  const std::vector<std::uint8_t> color = readTexture<std::uint8_t>(target->color, GL_RGBA, GL_UNSIGNED_BYTE, 4);
  ImageRgba8 image(frame.width, frame.height);
  const std::size_t rowBytes = std::size_t(frame.width) * 4;
  for (int j = 0; j < frame.height; ++j)
    std::memcpy(image.pixels.data() + std::size_t(j) * rowBytes,
                color.data() + std::size_t(frame.height - 1 - j) * rowBytes, rowBytes);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return image;
}

// Draws the overlays into the bound target's colour (depth-tested against its depth); the
// caller's scissor, if any, limits them.
void ImplicitTracer::Gpu::drawOverlayContent(const TraceFrame& frame, const HermiteSamples<3>* samples) {
  const TraceSettings& settings = frame.settings;
  target->bind();
  target->setColorOnly();
  OverlayContent content;
  content.samples = samples;
  content.showPoints = settings.showPoints;
  content.showNormals = settings.showNormals;
  content.showBounds = settings.showBounds;
  content.showGround = settings.showGround;
  content.groundUp = Vec<3>(settings.groundUp[0], settings.groundUp[1], settings.groundUp[2]);
  content.bounds = frame.bounds;
  scaleMarksToSpacing(frame, content);
  overlay->draw(frame.camera, frame.viewProj, content);
  target->setAllBuffers();
}

// A frame in passes: the GPU trace; the CPU refinement of its hits against the true field (or,
// unrefined, the GPU's hits as they are) and the composite with the slice plane; the overlays.
// With `deferred`, a baked refining frame leaves the refinement to refineDeferred.
TraceResult ImplicitTracer::render(const Camera& camera, const TraceSettings& settings, DeferredRefinement* deferred) {
  beginFrame(camera, settings);
  traceRows(std::numeric_limits<double>::infinity());
  return finishFrame(deferred);
}

void ImplicitTracer::beginFrame(const Camera& camera, const TraceSettings& settings, bool halfTilePass) {
  frame_.reset();
  if (!bake_ || !field_) throw InputError("implicit tracer: render before upload");
  if (settings.mode == TracerMode::Exact && !radialSum_)
    throw InputError("implicit tracer: exact mode needs an HRBF or RBF-offset model");
  const KeepFramebuffer keep;
  auto f = std::make_unique<Frame>(camera, settings);
  const TraceFrame& frame = f->frame.emplace(f->camera, f->settings, bounds_, *bake_, depthRange(camera));
  gpu_->targetFor(frame.width, frame.height);
  TraceResult& result = f->result;
  result.sliceRange = settings.slice.enabled ? frame.sliceRange : 0.0;
  result.sliceIsoSpacing = settings.slice.enabled ? niceIsoSpacing(frame.sliceRange) : 0.0;
  const auto t0 = Clock::now();
  result.exactDouble = settings.mode == TracerMode::Exact &&
                       (settings.exactPrecision == ExactPrecision::Double ||
                        (settings.exactPrecision == ExactPrecision::Auto && exactNeedsDouble()));
  // The baked mode's tile pass here (with halfTilePass its first half; the next traceRows runs
  // the rest); its read-back, the clear and the rectangles (prepareRects) open the first
  // traceRows after it, within its budget.
  const int tileRows = gpu_->tilePassRows(frame);
  f->tileRows = halfTilePass ? tileRows / 2 : tileRows;
  result.tracedPixels = gpu_->prepareTrace(frame, *bake_, f->tileRows);
  result.traceMs = msSince(t0);
  frame_ = std::move(f);
}

bool ImplicitTracer::frameStarted() const { return frame_ != nullptr; }

// Bands of at least kMinBandRows rows; the first of a frame has kFirstBandRows (its time per row sizes
// the next), later ones as many as the budget left allows at the largest time per row of a band so
// far (rows through the model cost several times the empty ones above it: the frame's average
// would let a band overrun the budget).
bool ImplicitTracer::traceRows(double budgetMs) {
  constexpr int kMinBandRows = 8, kFirstBandRows = 16;
  if (!frame_) throw InputError("implicit tracer: traceRows without beginFrame");
  Frame& f = *frame_;
  const TraceFrame& frame = *f.frame;
  const KeepFramebuffer keep;
  const auto t0 = Clock::now();
  if (const int all = gpu_->tilePassRows(frame); f.tileRows < all) {  // the tile pass's second half
    gpu_->runTilePass(frame, *bake_, f.tileRows, all);
    f.tileRows = all;
    f.result.traceMs += msSince(t0);
    if (std::isfinite(budgetMs)) return false;
  }
  if (f.result.tracedPixels < 0) f.result.tracedPixels = gpu_->prepareRects(frame);
  if (!std::isfinite(budgetMs)) {
    gpu_->traceRows(frame, *bake_, radialSum_, f.result.exactDouble, f.nextRow, frame.height);
    f.nextRow = frame.height;
  }
  while (f.nextRow < frame.height) {
    const double msPerRow = f.maxMsPerRow;
    const double left = budgetMs - msSince(t0);
    const int wanted = msPerRow > 0 ? int(left / msPerRow) : kFirstBandRows;
    const int rows = std::clamp(wanted, std::min(kMinBandRows, frame.height - f.nextRow), frame.height - f.nextRow);
    const auto band = Clock::now();
    gpu_->traceRows(frame, *bake_, radialSum_, f.result.exactDouble, f.nextRow, f.nextRow + rows);
    f.maxMsPerRow = std::max(f.maxMsPerRow, msSince(band) / rows);
    f.nextRow += rows;
    if (msSince(t0) + kMinBandRows * f.maxMsPerRow > budgetMs) break;
  }
  f.result.traceMs += msSince(t0);
  return f.nextRow >= frame.height;
}

bool ImplicitTracer::readBackStep() {
  if (!frame_ || frame_->nextRow < frame_->frame->height)
    throw InputError("implicit tracer: readBackStep before every row is traced");
  Frame& f = *frame_;
  const TraceTarget& target = *gpu_->target;
  if (!f.surfaceT && !f.hitData) {
    f.hitData = readHitTexture(target);
    return false;  // its conversion is left
  }
  if (!f.surfaceT) {
    f.surfaceT = surfaceHits(*f.hitData, target.width, target.height, f.result);
    f.hitData.reset();
    f.undecided = undecidedPixels(*f.surfaceT);
  } else if (!f.pass) {
    f.pass = readTracePass(target);
  }
  // finishFrame reads the trace pass only when it refines (or composites the undecided pixels).
  return f.pass || !((f.settings.refineExact || !f.undecided->empty()) && f.settings.showSurface);
}

TraceResult ImplicitTracer::finishFrame(DeferredRefinement* deferred) {
  if (!frame_ || frame_->nextRow < frame_->frame->height)
    throw InputError("implicit tracer: finishFrame before every row is traced");
  const std::unique_ptr<Frame> f = std::move(frame_);
  const TraceFrame& frame = *f->frame;
  const Camera& camera = f->camera;
  const TraceSettings& settings = f->settings;
  TraceTarget& target = *gpu_->target;
  TraceResult result = std::move(f->result);

  std::vector<float> surfaceT = f->surfaceT  ? std::move(*f->surfaceT)
                               : f->hitData ? surfaceHits(*f->hitData, target.width, target.height, result)
                                            : readSurfaceHits(target, result);
  std::vector<int> undecided = f->undecided ? std::move(*f->undecided) : undecidedPixels(surfaceT);
  result.cpuTracedPixels = int(undecided.size());
  const bool refine = (settings.refineExact || !undecided.empty()) && settings.showSurface;
  const auto tracePass = [&] { return f->pass ? std::move(*f->pass) : readTracePass(target); };
  if (refine && deferred && settings.mode == TracerMode::Baked) {
    DeferredRefinement& job = *deferred;
    job = DeferredRefinement{};
    job.camera = camera;
    job.settings = settings;
    job.bounds = bounds_;
    job.depthRange = depthRange(camera);
    job.bake = bake_;
    job.field = field_;
    TracePassPixels pass = tracePass();
    job.color = std::move(pass.color);
    job.planeColor = std::move(pass.planeColor);
    job.depth = std::move(pass.depth);
    job.result = result;
    job.surfaceT = surfaceT;
    job.undecided = std::move(undecided);
    keepVisibleSurface(frame, surfaceT, result);
  } else if (refine) {
    const auto t0 = Clock::now();
    const HitRefinement hits = refineHits(*field_, bounds_, camera, GpuHits{surfaceT, result.normal, undecided},
                                          refinementOptions(settings, *bake_, nullptr));
    result.ringHits = hits.ringHits;
    result.droppedHits = hits.droppedHits;
    TracePassPixels pass = tracePass();
    result.refinedPixels = compositeRefinedPixels(frame, hits, pass.planeColor, pass.color, pass.depth, result);
    writeTracePass(target, pass.color, pass.depth);
    result.refineMs = msSince(t0);
  } else {
    keepVisibleSurface(frame, surfaceT, result);
  }

  const auto t0 = Clock::now();
  result.image = gpu_->drawOverlays(frame, hasSamples_ ? &samples_ : nullptr);
  result.overlayMs = msSince(t0);
  return result;
}

void refineDeferred(DeferredRefinement& job, const CancelToken* cancel) {
  if (!job.camera || !job.bake || !job.field) throw InputError("implicit tracer: refinement of an empty job");
  const auto t0 = Clock::now();
  const TraceFrame frame(*job.camera, job.settings, job.bounds, *job.bake, job.depthRange);
  TraceResult& result = job.result;
  // The GPU's normals as read back: refineHits reads them while the bands composite into result.
  const std::vector<float> gpuNormal = result.normal;
  HitRefinementOptions options = refinementOptions(job.settings, *job.bake, cancel);
  int refined = 0;
  options.onBand = [&](const HitRefinement& partial, int rowBegin, int rowEnd) {
    refined += compositeRefinedPixels(frame, partial, job.planeColor, job.color, job.depth, result, rowBegin, rowEnd);
    job.rowsDone->store(rowEnd, std::memory_order_release);
  };
  const HitRefinement hits =
      refineHits(*job.field, job.bounds, *job.camera, GpuHits{job.surfaceT, gpuNormal, job.undecided}, options);
  result.ringHits = hits.ringHits;
  result.droppedHits = hits.droppedHits;
  result.refinedPixels = refined;
  result.refineMs = msSince(t0);
  job.refined = true;
}

TraceResult ImplicitTracer::finishDeferred(DeferredRefinement& job) {
  if (!job.refined || !job.camera) throw InputError("implicit tracer: finishing a refinement that did not run");
  frame_.reset();  // the target is overwritten
  const TraceFrame frame(*job.camera, job.settings, job.bounds, *job.bake, job.depthRange);
  const TraceTarget& target = gpu_->targetFor(frame.width, frame.height);
  writeTracePass(target, job.color, job.depth);
  TraceResult result = std::move(job.result);
  const auto t0 = Clock::now();
  result.image = gpu_->drawOverlays(frame, hasSamples_ ? &samples_ : nullptr);
  result.overlayMs = msSince(t0);
  return result;
}

void ImplicitTracer::finishDeferredRows(const DeferredRefinement& job, int rowBegin, int rowEnd, ImageRgba8& image,
                                        std::vector<float>& depth) {
  if (!job.camera || !job.bake) throw InputError("implicit tracer: rows of an empty refinement");
  frame_.reset();  // the target is overwritten
  const TraceFrame frame(*job.camera, job.settings, job.bounds, *job.bake, job.depthRange);
  const int W = frame.width, H = frame.height;
  rowBegin = std::clamp(rowBegin, 0, H);
  rowEnd = std::clamp(rowEnd, rowBegin, H);
  if (rowEnd == rowBegin) return;
  if (image.width != W || image.height != H || depth.size() != std::size_t(W) * H)
    throw InputError("implicit tracer: refined rows into an image of another size");
  const TraceTarget& target = gpu_->targetFor(W, H);
  // Top rows [rowBegin, rowEnd) are GL rows [H − rowEnd, H − rowBegin).
  const int glRow = H - rowEnd, rows = rowEnd - rowBegin;
  const std::size_t first = std::size_t(glRow) * W, count = std::size_t(rows) * W;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(target.color.id(), 0, 0, glRow, W, rows, GL_RGBA, GL_UNSIGNED_BYTE, &job.color[4 * first]);
  glTextureSubImage2D(target.depth.id(), 0, 0, glRow, W, rows, GL_DEPTH_COMPONENT, GL_FLOAT, &job.depth[first]);
  checkGl("implicit tracer refined rows upload");
  {
    const RowScissor scissor(W, H, glRow, glRow + rows);
    gpu_->drawOverlayContent(frame, hasSamples_ ? &samples_ : nullptr);
  }
  std::vector<std::uint8_t> color(4 * count);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(target.color.id(), 0, 0, glRow, 0, W, rows, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                       GLsizei(color.size()), color.data());
  checkGl("implicit tracer refined rows read-back");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const std::size_t rowBytes = std::size_t(W) * 4;
  for (int j = rowBegin; j < rowEnd; ++j) {
    std::memcpy(image.pixels.data() + std::size_t(j) * rowBytes, &color[std::size_t(rowEnd - 1 - j) * rowBytes],
                rowBytes);
    std::memcpy(&depth[std::size_t(j) * W], &job.result.depth[std::size_t(j) * W], std::size_t(W) * sizeof(float));
  }
}

}  // namespace hermite::render
