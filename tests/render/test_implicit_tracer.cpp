#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "core/base/errors.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/analytic_shapes.h"
#include "core/shapes/presets.h"
#include "core/trace/color_map.h"
#include "core/trace/cpu_tracer.h"
#include "core/trace/default_view_bounds.h"
#include "core/trace/shading.h"
#include "core/trace/volume_bake.h"
#include "io/png_file.h"
#include "render/implicit_tracer.h"
#include "render/staged_volume_upload.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

// min(f₁, f₂): a union of two spheres (Lipschitz 1 like each of them).
class TwoSpheres final : public ImplicitField<3> {
 public:
  TwoSpheres(const SphereField& a, const SphereField& b) : a_(a), b_(b) {}
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    const double fa = a_.evaluate(x), fb = b_.evaluate(x);
    return fa <= fb ? a_.evaluate(x, g, H) : b_.evaluate(x, g, H);
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

 private:
  SphereField a_, b_;
};

Box<3> cube(double h) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-h);
  b.hi = Vec<3>::Constant(h);
  return b;
}

Camera makeCamera(int w, int h, Projection projection = Projection::Perspective,
                  std::array<double, 3> eye = {1.8, 2.2, 2.6}, double halfHeight = 1.5) {
  CameraSpec spec;
  spec.eye = eye;
  return Camera(spec, projection, w, h, halfHeight);
}

struct Comparison {
  double iou = 0;
  double medianAngleDeg = 180;
  int both = 0;
  bool backgroundExact = true;
};

Comparison compare(const TraceResult& gpu, const CpuTraceResult& cpu, const std::array<double, 3>& background) {
  Comparison c;
  c.iou = maskIoU(gpu.hit, cpu.hit);
  std::vector<double> angles;
  const int W = gpu.image.width, H = gpu.image.height;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t p = std::size_t(j) * W + i;
      if (gpu.hit[p] && cpu.hit[p]) {
        const double d = std::clamp(gpu.normalAt(i, j).dot(cpu.normalAt(i, j)), -1.0, 1.0);
        angles.push_back(std::acos(d) * 180.0 / M_PI);
      }
      if (!gpu.hit[p]) {
        const std::uint8_t* px = gpu.image.at(i, j);
        for (int k = 0; k < 3; ++k)
          if (px[k] != shading::toByte(background[k])) c.backgroundExact = false;
      }
    }
  c.both = int(angles.size());
  if (!angles.empty()) {
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    c.medianAngleDeg = angles[angles.size() / 2];
  }
  return c;
}

void checkAgainstReference(ImplicitTracer& tracer, const ImplicitField<3>& field, const Box<3>& bounds,
                           const Camera& camera, TraceSettings settings) {
  const CpuTraceResult reference = traceImage(field, camera, bounds, settings.background);
  for (bool refine : {false, true}) {
    CAPTURE(refine);
    settings.refineExact = refine;
    const TraceResult result = tracer.render(camera, settings);
    const Comparison c = compare(result, reference, settings.background);
    CAPTURE(c.iou);
    CAPTURE(c.medianAngleDeg);
    CAPTURE(result.ringHits);
    CAPTURE(result.droppedHits);
    CHECK(c.both > 100);
    CHECK(c.iou >= 0.99);
    CHECK(c.medianAngleDeg <= 2.0);
    CHECK(c.backgroundExact);
    if (refine) {
      // Refined hits are shaded exactly like the reference: the bytes agree on common pixels.
      int differing = 0;
      for (int j = 0; j < camera.height(); ++j)
        for (int i = 0; i < camera.width(); ++i) {
          const std::size_t p = std::size_t(j) * camera.width() + i;
          if (!result.hit[p] || !reference.hit[p]) continue;
          for (int k = 0; k < 3; ++k)
            if (std::abs(int(result.image.at(i, j)[k]) - int(reference.image.at(i, j)[k])) > 2) {
              ++differing;
              break;
            }
        }
      CHECK(differing <= c.both / 100);
    }
  }
}

HrbfModel<3> fittedTorus(int count, HermiteSamples<3>* samplesOut = nullptr) {
  const HermiteSamples<3> samples = makePreset3d("torus", count);
  HrbfOptions options;
  options.kernel = Kernel{KernelType::Cubic, 1.0};
  options.polynomial = Polynomial::Linear;
  if (samplesOut) *samplesOut = samples;
  return fitHrbf(samples, options);
}

// A frame traced in pieces (bands, read-back steps) against the same frame rendered whole: the
// same bytes in every buffer and the same counts.
void checkSameTrace(const TraceResult& pieces, const TraceResult& whole) {
  CHECK(pieces.image == whole.image);
  CHECK(pieces.hit == whole.hit);
  CHECK(pieces.depth == whole.depth);
  CHECK(pieces.normal == whole.normal);
  CHECK(pieces.tracedPixels == whole.tracedPixels);
  CHECK(pieces.refinedPixels == whole.refinedPixels);
}

}  // namespace

TEST_CASE("implicit tracer: baked sphere and torus match the CPU reference") {
  auto context = testing::makeTestContext();
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 64;
  TraceSettings settings;
  settings.background = {0.2, 0.3, 0.4};
  SUBCASE("sphere") {
    const SphereField sphere(Vec<3>(0.1, -0.05, 0.0), 0.9);
    const Box<3> bounds = cube(1.3);
    tracer.upload(sphere, bounds, nullptr, upload);
    checkAgainstReference(tracer, sphere, bounds, makeCamera(80, 64), settings);
  }
  SUBCASE("torus") {
    const TorusField torus;
    const Box<3> bounds = cube(1.25);
    tracer.upload(torus, bounds, nullptr, upload);
    checkAgainstReference(tracer, torus, bounds, makeCamera(80, 64), settings);
  }
}

TEST_CASE("implicit tracer: baked fitted HRBF matches the CPU reference") {
  auto context = testing::makeTestContext();
  ImplicitTracer tracer;
  HermiteSamples<3> samples;
  const HrbfModel<3> model = fittedTorus(150, &samples);
  const Box<3> bounds = defaultViewBounds<3>(samples.points);
  TracerUploadOptions upload;
  upload.bakeResolution = 64;
  tracer.upload(model, bounds, &samples, upload);
  TraceSettings settings;
  checkAgainstReference(tracer, model, bounds, makeCamera(72, 64), settings);
}

TEST_CASE("implicit tracer: exact shader mode matches the CPU reference at 64x64") {
  auto context = testing::makeTestContext();
  ImplicitTracer tracer;
  HermiteSamples<3> samples;
  const HrbfModel<3> model = fittedTorus(60, &samples);
  const Box<3> bounds = defaultViewBounds<3>(samples.points);
  TracerUploadOptions upload;
  upload.bakeResolution = 32;
  tracer.upload(model, bounds, &samples, upload);
  REQUIRE(tracer.hasExactModel());
  TraceSettings settings;
  settings.mode = TracerMode::Exact;
  settings.refineExact = false;
  const Camera camera = makeCamera(64, 64);
  const CpuTraceResult reference = traceImage(model, camera, bounds, settings.background);
  const TraceResult result = tracer.render(camera, settings);
  const Comparison c = compare(result, reference, settings.background);
  CAPTURE(c.iou);
  CAPTURE(c.medianAngleDeg);
  CHECK(c.both > 100);
  CHECK(c.iou >= 0.99);
  CHECK(c.medianAngleDeg <= 2.0);
  CHECK(c.backgroundExact);
}

TEST_CASE("implicit tracer: a tiny far-away bubble is visible") {
  auto context = testing::makeTestContext();
  const Box<3> bounds = cube(1.5);
  const TwoSpheres field(SphereField(Vec<3>::Zero(), 0.6), SphereField(Vec<3>(1.3, 1.3, -1.3), 0.08));
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 64;
  tracer.upload(field, bounds, nullptr, upload);
  const Camera camera = makeCamera(96, 96, Projection::Perspective, {3.0, 2.0, 4.0});
  TraceSettings settings;
  const TraceResult result = tracer.render(camera, settings);
  const Vec<2> c = camera.project(Vec<3>(1.3, 1.3, -1.3));
  int bubble = 0;
  for (int j = 0; j < 96; ++j)
    for (int i = 0; i < 96; ++i)
      if (result.hit[std::size_t(j) * 96 + i] && std::hypot(i + 0.5 - c.x(), j + 0.5 - c.y()) < 4.0) ++bubble;
  CHECK(bubble >= 3);
  const CpuTraceResult reference = traceImage(field, camera, bounds, settings.background);
  CHECK(maskIoU(result.hit, reference.hit) >= 0.99);
}

namespace {

// min over spheres of (‖x − c‖ − r).
class SphereSet final : public ImplicitField<3> {
 public:
  void add(const Vec<3>& centre, double radius) {
    centres_.push_back(centre);
    radii_.push_back(radius);
  }
  // A big sphere among small ones scattered through [-1.3, 1.3]³, some barely a bake cell
  // across, so that pixel rays graze and just miss many of them.
  static SphereSet scattered() {
    SphereSet set;
    set.add(Vec<3>::Zero(), 0.55);
    unsigned state = 12345u;
    auto next = [&state] {
      state = state * 1664525u + 1013904223u;
      return double(state >> 8) / double(1u << 24);
    };
    for (int k = 0; k < 200; ++k) {
      const Vec<3> c(2.6 * next() - 1.3, 2.6 * next() - 1.3, 2.6 * next() - 1.3);
      set.add(c, 0.025 + 0.05 * next());
    }
    return set;
  }
  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override {
    std::size_t best = 0;
    double f = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < centres_.size(); ++k) {
      const double v = (x - centres_[k]).norm() - radii_[k];
      if (v < f) {
        f = v;
        best = k;
      }
    }
    return SphereField(centres_[best], radii_[best]).evaluate(x, g, H);
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

 private:
  std::vector<Vec<3>> centres_;
  std::vector<double> radii_;
};

// The scattered spheres baked at 96³ over [-1.5, 1.5]³ (needs a current context).
struct ScatteredSpheresScene {
  SphereSet field = SphereSet::scattered();
  ImplicitTracer tracer;
  ScatteredSpheresScene() {
    TracerUploadOptions upload;
    upload.bakeResolution = 96;
    tracer.upload(field, cube(1.5), nullptr, upload);
  }
};

// Pixels of `result` (a baked trace without refinement) whose first zero a brute-force walk of
// the bake's interpolant (steps of 1/16 cell) finds, and how many of those the trace lost or
// found more than a quarter cell later.
struct FirstZeroCheck {
  int walkHits = 0, lost = 0, late = 0;
};

FirstZeroCheck checkFirstZeros(const TraceResult& result, const VolumeBake& bake, const Camera& camera) {
  const double cell = bake.spacing().minCoeff();
  FirstZeroCheck out;
  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i) {
      const Ray ray = camera.pixelRay(i, j);
      double t0, t1;
      double tWalk = -1;
      if (clipRayToBox(ray, bake.bounds, t0, t1)) {
        const double step = cell / 16;
        const bool negative = bake.interpolate(ray.at(t0)) < 0;
        for (double t = t0 + step; t <= t1 && tWalk < 0; t += step)
          if ((bake.interpolate(ray.at(t)) < 0) != negative) tWalk = t;
      }
      if (tWalk < 0) continue;
      ++out.walkHits;
      const std::size_t p = std::size_t(j) * camera.width() + i;
      if (!result.hit[p])
        ++out.lost;
      else if (result.depth[p] > tWalk + 0.25 * cell)
        ++out.late;
    }
  return out;
}

}  // namespace

// The baked trace skips empty space per tile of pixels before each pixel marches
// (trace_tile_pass.glsl). No pixel may find its first zero of the interpolant later than a
// brute-force walk does, or lose it, beyond the march's own ε-step resolution — from outside,
// from inside the bounds, in both projections.
TEST_CASE("implicit tracer: the baked march finds the interpolant's first zero on every pixel") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  struct View {
    std::string name;
    Camera camera;
  };
  const View views[] = {
      {"perspective, outside", makeCamera(128, 96, Projection::Perspective, {2.6, 3.1, 3.7})},
      {"perspective, eye inside the bounds", makeCamera(128, 96, Projection::Perspective, {1.2, -1.1, 0.9})},
      {"orthographic", makeCamera(120, 90, Projection::Orthographic, {1.8, 2.2, 2.6}, 1.6)},
  };
  for (const View& view : views) {
    CAPTURE(view.name);
    TraceSettings settings;
    settings.refineExact = false;
    const FirstZeroCheck c = checkFirstZeros(tracer.render(view.camera, settings), tracer.bake(), view.camera);
    CAPTURE(c.walkHits);
    CAPTURE(c.lost);
    CAPTURE(c.late);
    CHECK(c.walkHits > view.camera.width() * view.camera.height() / 20);
    // A zero pair closer together than the ε step (0.1 cell) may pass between two samples of
    // the march: a handful of grazing pixels, never a missing patch.
    CHECK(c.lost + c.late <= std::max(3, c.walkHits / 500));
  }
}

// Small spheres, each hit by a tile's corner pixel and missed by the ray through the tile's
// centre: only a tile pass whose cone holds all of the tile's rays sees them.
TEST_CASE("implicit tracer: objects that only a tile's corner pixels see are drawn") {
  auto context = testing::makeTestContext();
  for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
    CAPTURE(int(projection));
    const Camera camera = makeCamera(64, 64, projection, {0.0, 0.0, 3.0}, 1.0);
    SphereSet field;
    const double pixel = 2.0 * 1.0 / 64;  // world size of a pixel near z = 0 (both cameras roughly)
    for (int a = 1; a < 15; a += 3)
      for (int b = 1; b < 15; b += 4) {
        const Ray ray = camera.pixelRay(4 * a, 4 * b);  // the corner pixel of tile (a, b)
        const double t = (0.2 - ray.origin.z()) / ray.direction.z();
        field.add(ray.at(t), 0.6 * pixel);
      }
    ImplicitTracer tracer;
    TracerUploadOptions upload;
    upload.bakeResolution = 160;
    tracer.upload(field, cube(1.0), nullptr, upload);
    TraceSettings settings;
    settings.refineExact = false;
    const FirstZeroCheck c = checkFirstZeros(tracer.render(camera, settings), tracer.bake(), camera);
    CAPTURE(c.walkHits);
    CAPTURE(c.lost);
    CAPTURE(c.late);
    CHECK(c.walkHits >= 20);
    CHECK(c.lost + c.late == 0);
  }
}

// The trace pass skips the tiles the tile pass proved empty (tile_spans.h) and clears them to
// what a miss writes: the same bytes, hits, depths and normals as tracing every pixel.
TEST_CASE("implicit tracer: skipping empty tiles changes no pixel") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera cameras[] = {
      makeCamera(130, 98, Projection::Perspective, {2.6, 3.1, 3.7}),  // not multiples of the tile
      makeCamera(128, 96, Projection::Perspective, {1.2, -1.1, 0.9}),  // eye inside the bounds
      makeCamera(121, 90, Projection::Orthographic, {1.8, 2.2, 2.6}, 1.6),
      makeCamera(96, 96, Projection::Perspective, {9.0, 7.0, 8.0}),  // far: most tiles empty
  };
  for (const Camera& camera : cameras) {
    CAPTURE(camera.width());
    for (bool refine : {false, true}) {
      CAPTURE(refine);
      TraceSettings settings;
      settings.refineExact = refine;
      settings.background = {0.2, 0.3, 0.4};
      settings.showPoints = true;
      settings.skipEmptyTiles = false;
      const TraceResult all = tracer.render(camera, settings);
      settings.skipEmptyTiles = true;
      const TraceResult skipped = tracer.render(camera, settings);
      const long long pixels = (long long)camera.width() * camera.height();
      CHECK(all.tracedPixels == pixels);
      CHECK(skipped.tracedPixels < pixels);
      CHECK(skipped.tracedPixels > 0);
      CHECK(skipped.image == all.image);
      CHECK(skipped.hit == all.hit);
      CHECK(skipped.depth == all.depth);
      CHECK(skipped.normal == all.normal);
    }
  }
}

TEST_CASE("implicit tracer: orthographic projection matches the CPU reference") {
  auto context = testing::makeTestContext();
  const TorusField torus;
  const Box<3> bounds = cube(1.25);
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 64;
  tracer.upload(torus, bounds, nullptr, upload);
  checkAgainstReference(tracer, torus, bounds, makeCamera(80, 64, Projection::Orthographic, {1.8, 2.2, 2.6}, 1.3),
                        TraceSettings{});
}

TEST_CASE("implicit tracer: slice plane shows the zero circle of a sphere cut through its centre") {
  auto context = testing::makeTestContext();
  const SphereField sphere(Vec<3>::Zero(), 0.8);
  const Box<3> bounds = cube(1.2);
  ImplicitTracer tracer;
  TracerUploadOptions upload;
  upload.bakeResolution = 64;
  tracer.upload(sphere, bounds, nullptr, upload);
  const int N = 96;
  const Camera camera = makeCamera(N, N, Projection::Orthographic, {0, 0, 4}, 1.2);
  TraceSettings settings;
  settings.slice.enabled = true;
  settings.slice.normal = {0, 0, 1};
  settings.slice.offset = 0.0;
  for (bool surface : {false, true}) {
    CAPTURE(surface);
    settings.showSurface = surface;
    const TraceResult result = tracer.render(camera, settings);
    const double radiusPx = 0.8 / (2.0 * 1.2 / N);
    int zero = 0, outside = 0, heat = 0;
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        const std::uint8_t* px = result.image.at(i, j);
        const double r = std::hypot(i + 0.5 - N / 2.0, j + 0.5 - N / 2.0);
        if (px[0] == 0 && px[1] == 0 && px[2] == 0) {
          ++zero;
          if (std::abs(r - radiusPx) > 1.5) ++outside;
        } else if (!result.hit[std::size_t(j) * N + i]) {
          ++heat;
        }
      }
    CAPTURE(zero);
    CHECK(outside == 0);
    // A 2 px band (or its outer half when the surface hides the inside) around 2πr.
    CHECK(zero >= (surface ? 0.8 : 1.6) * 2 * M_PI * radiusPx);
    CHECK(heat > N * N / 2);
  }
}

namespace {

// The unit sphere's field with `samples` into `tracer`, baked at 48³ over the samples' view bounds.
void uploadSphere(ImplicitTracer& tracer, const SphereField& sphere, const HermiteSamples<3>& samples) {
  TracerUploadOptions upload;
  upload.bakeResolution = 48;
  tracer.upload(sphere, defaultViewBounds<3>(samples.points), &samples, upload);
}

}  // namespace

TEST_CASE("implicit tracer: overlays are drawn and hidden behind the surface") {
  auto context = testing::makeTestContext();
  HermiteSamples<3> samples = makePreset3d("sphere6", 0);
  const SphereField sphere;
  ImplicitTracer tracer;
  uploadSphere(tracer, sphere, samples);
  const Camera camera = makeCamera(96, 96, Projection::Perspective, {1.5, 1.2, 3.5});
  REQUIRE((camera.project(Vec<3>(0, 0, 1)) - camera.project(Vec<3>(0, 0, -1))).norm() > 8);
  TraceSettings settings;
  settings.showPoints = true;
  settings.showNormals = true;
  settings.showBounds = true;
  const TraceResult result = tracer.render(camera, settings);
  auto near = [&](const Vec<3>& x) {
    const Vec<2> p = camera.project(x);
    int dark = 0;
    for (int j = int(p.y()) - 2; j <= int(p.y()) + 2; ++j)
      for (int i = int(p.x()) - 2; i <= int(p.x()) + 2; ++i) {
        const std::uint8_t* px = result.image.at(i, j);
        if (px[0] < 40 && px[1] < 40 && px[2] < 40) ++dark;
      }
    return dark;
  };
  CHECK(near(Vec<3>(0, 0, 1)) >= 4);   // the sample facing the camera
  CHECK(near(Vec<3>(0, 0, -1)) == 0);  // the one behind the sphere is hidden
  // The bounds box draws lines on the background.
  int boxPixels = 0;
  for (std::size_t p = 0; p < result.hit.size(); ++p) {
    const std::uint8_t* px = result.image.pixels.data() + 4 * p;
    if (!result.hit[p] && px[0] == 89 && px[1] == 89 && px[2] == 89) ++boxPixels;
  }
  CHECK(boxPixels > 50);
}

TEST_CASE("implicit tracer: samples closer than 2 px on screen get no dots, until the view comes closer") {
  // 20 000 samples of the unit sphere are about 0.025 apart: under 1 px at 96 × 96 from 4 units
  // off, where 2 px dots would cover the sphere; 5 px apart from 1.5 units off at 480 × 480.
  auto context = testing::makeTestContext();
  HermiteSamples<3> samples;  // a golden spiral: evenly spread, outward normals
  samples.points.resize(3, 20000);
  for (int i = 0; i < 20000; ++i) {
    const double z = 1 - (2 * i + 1) / 20000.0, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
    samples.points.col(i) = Vec<3>(r * std::cos(phi), r * std::sin(phi), z);
  }
  samples.normals = samples.points;
  const SphereField sphere;
  ImplicitTracer tracer;
  uploadSphere(tracer, sphere, samples);
  using Eye = std::array<double, 3>;
  for (const auto& [size, eye, drawn] : {std::tuple{96, Eye{0, 0, 4}, false}, std::tuple{480, Eye{0, 0, 1.5}, true}}) {
    CAPTURE(size);
    const Camera camera = makeCamera(size, size, Projection::Perspective, eye);
    TraceSettings settings;
    settings.showPoints = false;
    const TraceResult plain = tracer.render(camera, settings);
    settings.showPoints = true;
    const TraceResult dotted = tracer.render(camera, settings);
    CHECK((dotted.image == plain.image) == !drawn);
  }
}

TEST_CASE("implicit tracer: deterministic bytes, and EGL agrees with OSMesa") {
  HermiteSamples<3> samples;
  const HrbfModel<3> model = fittedTorus(80, &samples);
  const Box<3> bounds = defaultViewBounds<3>(samples.points);
  TracerUploadOptions upload;
  upload.bakeResolution = 48;
  TraceSettings settings;
  settings.showPoints = true;
  settings.showNormals = true;
  settings.slice.enabled = true;
  settings.slice.normal = {0.2, 0.3, 1.0};
  settings.slice.offset = 0.05;
  const Camera camera = makeCamera(96, 80);
  ImageRgba8 osmesa;
  {
    auto context = testing::makeTestContext("osmesa");
    ImplicitTracer tracer;
    tracer.upload(model, bounds, &samples, upload);
    osmesa = tracer.render(camera, settings).image;
    if (std::getenv("HERMITE_TRACER_PNG")) writePng("/tmp/h5_tracer.png", osmesa);
    const ImageRgba8 again = tracer.render(camera, settings).image;
    CHECK(osmesa == again);
  }
  if (testing::skipEgl()) return;
  auto context = testing::makeTestContext("egl");
  ImplicitTracer tracer;
  tracer.upload(model, bounds, &samples, upload);
  const ImageRgba8 egl = tracer.render(camera, settings).image;
  const ImageDiffStats stats = compareImages(osmesa, egl, 2);
  CAPTURE(stats.maxChannelDiff);
  CHECK(stats.fractionOver <= 0.001);
}

TEST_CASE("implicit tracer: a frame traced in bands of rows has the bytes of a whole render") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(130, 98, Projection::Perspective, {2.6, 3.1, 3.7});
  for (bool slice : {false, true})
    for (bool refine : {false, true}) {
      CAPTURE(slice);
      CAPTURE(refine);
      TraceSettings settings;
      settings.refineExact = refine;
      settings.showBounds = true;
      settings.background = {0.2, 0.3, 0.4};
      settings.slice.enabled = slice;
      settings.slice.normal = {0.3, 0.2, 1.0};
      settings.slice.offset = 0.1;
      const TraceResult whole = tracer.render(camera, settings);
      tracer.beginFrame(camera, settings);
      int calls = 1;
      while (!tracer.traceRows(0.0)) ++calls;  // no budget: one band per call (16 rows, then 8)
      CHECK(calls == 1 + (98 - 16 + 7) / 8);
      CHECK(tracer.frameStarted());
      const TraceResult banded = tracer.finishFrame();
      CHECK_FALSE(tracer.frameStarted());
      checkSameTrace(banded, whole);
    }
}

TEST_CASE("implicit tracer: a tile pass run in two halves over two calls gives the bytes of a whole render") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(130, 98, Projection::Perspective, {2.6, 3.1, 3.7});
  for (bool refine : {false, true}) {
    CAPTURE(refine);
    TraceSettings settings;
    settings.refineExact = refine;
    settings.showBounds = true;
    const TraceResult whole = tracer.render(camera, settings);
    tracer.beginFrame(camera, settings, true);
    CHECK_FALSE(tracer.traceRows(1e9));  // a finite budget: the tile pass's second half alone
    int calls = 1;
    while (!tracer.traceRows(0.0)) ++calls;
    CHECK(calls == 1 + (98 - 16 + 7) / 8);  // then the bands as after a whole tile pass
    const TraceResult split = tracer.finishFrame();
    checkSameTrace(split, whole);
    CHECK(split.tracedPixels == whole.tracedPixels);  // the same tiles proven empty
  }
}

TEST_CASE("implicit tracer: a banded frame's deferred refinement matches the whole frame's") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(121, 90, Projection::Perspective, {1.8, 2.2, 2.6});
  TraceSettings settings;
  settings.showBounds = true;
  DeferredRefinement wholeJob, bandedJob;
  tracer.render(camera, settings, &wholeJob);
  refineDeferred(wholeJob);
  const TraceResult whole = tracer.finishDeferred(wholeJob);
  tracer.beginFrame(camera, settings);
  while (!tracer.traceRows(0.0)) {
  }
  tracer.finishFrame(&bandedJob);
  refineDeferred(bandedJob);
  const TraceResult banded = tracer.finishDeferred(bandedJob);
  CHECK(whole.refinedPixels > 100);
  CHECK(banded.image == whole.image);
  CHECK(banded.depth == whole.depth);
  CHECK(banded.refinedPixels == whole.refinedPixels);
}

TEST_CASE("implicit tracer: a banded frame read back over several calls has the bytes of a whole render") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(117, 86, Projection::Perspective, {2.6, 3.1, 3.7});
  for (bool refine : {false, true}) {
    CAPTURE(refine);
    TraceSettings settings;
    settings.refineExact = refine;
    settings.showBounds = true;
    const TraceResult whole = tracer.render(camera, settings);
    tracer.beginFrame(camera, settings);
    CHECK_THROWS_AS(tracer.readBackStep(), InputError);  // rows are left to trace
    while (!tracer.traceRows(0.0)) {
    }
    int steps = 1;
    while (!tracer.readBackStep()) ++steps;
    // The hit texture, its conversion, then (refining) the trace pass; a call after the last
    // finds nothing left.
    CHECK(steps == (refine ? 3 : 2));
    CHECK(tracer.readBackStep());
    const TraceResult banded = tracer.finishFrame();
    checkSameTrace(banded, whole);
  }
}

TEST_CASE("implicit tracer: refined rows copied while the refinement publishes them give finishDeferred's image") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(121, 90, Projection::Perspective, {1.8, 2.2, 2.6});
  TraceSettings settings;
  settings.showBounds = true;  // overlays drawn over the rows under a scissor
  DeferredRefinement wholeJob, rowJob;
  tracer.render(camera, settings, &wholeJob);
  refineDeferred(wholeJob);
  const TraceResult whole = tracer.finishDeferred(wholeJob);
  REQUIRE(whole.refinedPixels > 100);

  TraceResult baked = tracer.render(camera, settings, &rowJob);
  CHECK(rowJob.rowsDone->load() == 0);
  ImageRgba8 image = baked.image;
  std::vector<float> depth = baked.depth;
  REQUIRE(!(image == whole.image));  // the refinement changes pixels, so the copy is seen
  // The refinement publishes bands on a worker; this (GL) thread copies what is published.
  std::thread worker([&] { refineDeferred(rowJob); });
  int copied = 0, copies = 0;
  std::vector<int> published;
  while (copied < camera.height()) {
    const int done = rowJob.rowsDone->load(std::memory_order_acquire);
    if (done > copied) {
      tracer.finishDeferredRows(rowJob, copied, done, image, depth);
      published.push_back(done);
      copied = done, ++copies;
    }
    std::this_thread::yield();
  }
  worker.join();
  CHECK(std::is_sorted(published.begin(), published.end()));
  CHECK(copies >= 1);
  CHECK(image == whole.image);
  CHECK(depth == whole.depth);
  // Uneven chunks of a finished job, out of order: each row's bytes depend on that row only.
  ImageRgba8 again = baked.image;
  std::vector<float> againDepth = baked.depth;
  for (const auto& [a, b] : {std::pair{40, 90}, std::pair{0, 7}, std::pair{7, 40}})
    tracer.finishDeferredRows(rowJob, a, b, again, againDepth);
  CHECK(again == whole.image);
  CHECK(againDepth == whole.depth);
  ImageRgba8 small(10, 10);
  CHECK_THROWS_AS(tracer.finishDeferredRows(rowJob, 0, 5, small, againDepth), InputError);
}

TEST_CASE("implicit tracer: an upload or a render abandons a banded frame") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(64, 48);
  const TraceSettings settings;
  tracer.beginFrame(camera, settings);
  CHECK_FALSE(tracer.traceRows(0.0));
  tracer.render(camera, settings);
  CHECK_FALSE(tracer.frameStarted());
  CHECK_THROWS_AS(tracer.traceRows(0.0), InputError);
  tracer.beginFrame(camera, settings);
  TracerUploadOptions upload;
  upload.bakeResolution = 32;
  tracer.upload(scene.field, cube(1.5), nullptr, upload);
  CHECK_FALSE(tracer.frameStarted());
  CHECK_THROWS_AS(tracer.finishFrame(), InputError);
}

TEST_CASE("implicit tracer: a bake uploaded in slabs draws the previous bake until complete, then a whole upload's bytes") {
  auto context = testing::makeTestContext();
  ScatteredSpheresScene scene;  // the previous upload: the scattered spheres at 96³
  ImplicitTracer& tracer = scene.tracer;
  const Camera camera = makeCamera(96, 72, Projection::Perspective, {2.6, 3.1, 3.7});
  TraceSettings settings;
  settings.showBounds = true;
  const TraceResult before = tracer.render(camera, settings);
  const SphereField other(Vec<3>(0.2, -0.1, 0.1), 0.7);
  TracerUploadOptions options;
  options.bakeResolution = 40;  // 5 slabs of 8 z-slices, then the brick textures
  ImplicitTracer whole;
  whole.upload(other, cube(1.5), nullptr, options);
  const TraceResult expected = whole.render(camera, settings);
  REQUIRE_FALSE(expected.image == before.image);

  tracer.beginUpload(prepareTracerVolume(other, cube(1.5), options), other);
  CHECK(tracer.uploading());
  int calls = 0;
  while (!tracer.continueUpload(0.0)) {  // no budget: one step per call
    ++calls;
    CHECK(tracer.render(camera, settings).image == before.image);
  }
  CHECK(calls == 40 / StagedVolumeUpload::kSlabSlices);
  CHECK_FALSE(tracer.uploading());
  const TraceResult after = tracer.render(camera, settings);
  CHECK(after.image == expected.image);
  CHECK(after.depth == expected.depth);
  CHECK(tracer.bake().resolution == 40);
}
