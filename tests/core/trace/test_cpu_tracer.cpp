#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/base/errors.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/analytic_shapes.h"
#include "core/trace/cpu_tracer.h"
#include "core/trace/shading.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

CameraSpec cameraAt(Vec<3> eye) {
  CameraSpec s;
  s.eye = {eye.x(), eye.y(), eye.z()};
  return s;
}

Box<3> cube(double h) {
  Box<3> b;
  b.lo = Vec<3>::Constant(-h);
  b.hi = Vec<3>::Constant(h);
  return b;
}

// Analytic first intersection of a ray with a sphere (t ≥ 0), or −1.
double raySphere(const Ray& ray, const Vec<3>& c, double R) {
  const Vec<3> oc = ray.origin - c;
  const double b = oc.dot(ray.direction), q = oc.squaredNorm() - R * R;
  const double disc = b * b - q;
  if (disc < 0) return -1;
  const double t = -b - std::sqrt(disc);
  return t >= 0 ? t : -1;
}

// min(f₁, f₂) of two spheres: a union; Lipschitz 1.
class TwoSpheres final : public ImplicitField<3> {
 public:
  TwoSpheres(SphereField a, SphereField b) : a_(std::move(a)), b_(std::move(b)) {}
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    const double fa = a_.value(x), fb = b_.value(x);
    return fa <= fb ? a_.evaluate(x, g, H) : b_.evaluate(x, g, H);
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }

 private:
  SphereField a_, b_;
};

}  // namespace

TEST_CASE("cpu tracer: sphere silhouette, normals and exact background") {
  const Vec<3> centre(0.1, -0.05, 0.2);
  const double R = 0.8;
  const SphereField sphere(centre, R);
  const std::array<double, 3> bg{0.2, 0.3, 0.4};
  for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
    const Camera cam(cameraAt(Vec<3>(1.0, 1.5, 3.5)), proj, 128, 128, 1.2);
    const CpuTraceResult r = traceImage(sphere, cam, cube(1.25), bg);
    std::vector<std::uint8_t> analytic(128 * 128, 0);
    std::vector<double> angles;
    int backgroundExact = 0, misses = 0;
    for (int j = 0; j < 128; ++j)
      for (int i = 0; i < 128; ++i) {
        const std::size_t p = std::size_t(j) * 128 + i;
        const Ray ray = cam.pixelRay(i, j);
        const double t = raySphere(ray, centre, R);
        analytic[p] = t >= 0;
        if (r.hit[p] && t >= 0) {
          const Vec<3> n = (ray.at(t) - centre).normalized();
          angles.push_back(std::acos(std::clamp(n.dot(r.normalAt(i, j)), -1.0, 1.0)) * 180.0 / M_PI);
          CHECK(std::abs(r.depth[p] - t) < 1e-5);
          CHECK(r.back[p] == 0);
        }
        if (!r.hit[p]) {
          ++misses;
          const std::uint8_t* px = r.image.at(i, j);
          backgroundExact += px[0] == 51 && px[1] == 77 && px[2] == 102 && px[3] == 255;
        }
      }
    CHECK(maskIoU(r.hit, analytic) >= 0.99);
    REQUIRE(!angles.empty());
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    CHECK(angles[angles.size() / 2] < 0.5);
    CHECK(misses > 1000);
    CHECK(backgroundExact == misses);
  }
}

TEST_CASE("cpu tracer: shading of the centre pixel follows core/shading.h") {
  const SphereField sphere(Vec<3>::Zero(), 1.0);
  const Camera cam(cameraAt(Vec<3>(0, 0, 4)), Projection::Perspective, 33, 33, 1.5);
  const CpuTraceResult r = traceImage(sphere, cam, cube(1.25), {1, 1, 1});
  // Centre pixel: normal (0, 0, 1) = −f; lights in camera space.
  double light = shading::kAmbient;
  for (const shading::Light& l : shading::kLights)
    light += l.intensity * std::max(0.0, -l.f / std::sqrt(l.r * l.r + l.u * l.u + l.f * l.f));
  const std::uint8_t* px = r.image.at(16, 16);
  for (int k = 0; k < 3; ++k) CHECK(int(px[k]) == int(std::lround(255 * std::min(1.0, shading::kFrontColor[k] * light))));
}

TEST_CASE("cpu tracer: a tiny sphere far from the data is found, and inside views are back faces") {
  const TwoSpheres field(SphereField(Vec<3>::Zero(), 0.7), SphereField(Vec<3>(1.5, 1.1, 0.4), 0.05));
  const Camera cam(cameraAt(Vec<3>(0, 0, 5)), Projection::Perspective, 96, 96, 1.5);
  const CpuTraceResult r = traceImage(field, cam, cube(1.8), {1, 1, 1});
  const Vec<2> p = cam.project(Vec<3>(1.5, 1.1, 0.4));
  const int i = int(p.x()), j = int(p.y());
  REQUIRE(i >= 0);
  REQUIRE(j >= 0);
  CHECK(r.hit[std::size_t(j) * 96 + i] == 1);
  CHECK(r.depth[std::size_t(j) * 96 + i] == doctest::Approx((Vec<3>(1.5, 1.1, 0.4) - Vec<3>(0, 0, 5)).norm() - 0.05).epsilon(0.01));

  // Bounds cutting the big sphere open: rays start inside and hit it from within (back faces).
  Box<3> cut = cube(1.8);
  cut.hi.z() = 0.3;
  const CpuTraceResult inside = traceImage(field, cam, cut, {1, 1, 1});
  CHECK(inside.hit[48 * 96 + 48] == 1);
  CHECK(inside.back[48 * 96 + 48] == 1);
  CHECK(inside.depth[48 * 96 + 48] == doctest::Approx(5.7).epsilon(1e-3));
}

TEST_CASE("cpu tracer: an HRBF of sphere samples has no holes against the analytic sphere") {
  const HrbfModel<3> model = fitHrbf<3>(testing::goldenSphere(80), {});
  const Camera cam(cameraAt(Vec<3>(2, 1.5, 3)), Projection::Perspective, 64, 64, 1.5);
  const CpuTraceResult r = traceImage(model, cam, cube(1.25), {1, 1, 1});
  std::vector<std::uint8_t> analytic(64 * 64, 0);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) analytic[std::size_t(j) * 64 + i] = raySphere(cam.pixelRay(i, j), Vec<3>::Zero(), 1.0) >= 0;
  CHECK(maskIoU(r.hit, analytic) >= 0.97);
  // No speckles: every analytic-interior pixel away from the silhouette is hit.
  int holes = 0;
  for (int j = 1; j < 63; ++j)
    for (int i = 1; i < 63; ++i) {
      bool interior = true;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) interior = interior && analytic[std::size_t(j + dj) * 64 + i + di];
      holes += interior && !r.hit[std::size_t(j) * 64 + i];
    }
  CHECK(holes == 0);
}

TEST_CASE("cpu tracer: render (wavefront) and trace (one ray) agree") {
  const HrbfModel<3> model = fitHrbf<3>(testing::blob(40), {});
  const Camera cam(cameraAt(Vec<3>(1, 2, 3)), Projection::Perspective, 24, 24, 1.5);
  const CpuTracer tracer(model, cube(1.4));
  const CpuTraceResult r = tracer.render(cam, {1, 1, 1});
  for (int j = 0; j < 24; j += 3)
    for (int i = 0; i < 24; i += 5) {
      const RayHit h = tracer.trace(cam.pixelRay(i, j));
      const std::size_t p = std::size_t(j) * 24 + i;
      CHECK(h.hit == bool(r.hit[p]));
      if (h.hit) CHECK(float(h.t) == r.depth[p]);
    }
}
