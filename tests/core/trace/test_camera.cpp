#include <doctest/doctest.h>

#include "core/base/errors.h"
#include "core/trace/camera.h"
#include "scene/scene_file.h"

using namespace hermite;

namespace {

CameraSpec spec(Vec<3> eye, Vec<3> target, Vec<3> up, double fov) {
  CameraSpec s;
  s.eye = {eye.x(), eye.y(), eye.z()};
  s.target = {target.x(), target.y(), target.z()};
  s.up = {up.x(), up.y(), up.z()};
  s.fovYDeg = fov;
  return s;
}

// The camera.h ray formula, written out independently.
Vec<3> formulaDirection(const CameraSpec& s, int W, int H, int i, int j) {
  const Vec<3> eye(s.eye[0], s.eye[1], s.eye[2]), target(s.target[0], s.target[1], s.target[2]),
      up(s.up[0], s.up[1], s.up[2]);
  const Vec<3> f = (target - eye).normalized();
  const Vec<3> r = f.cross(up).normalized();
  const Vec<3> u = r.cross(f);
  const double t = std::tan(s.fovYDeg * M_PI / 360.0);
  return (f + (2.0 * (i + 0.5) / W - 1.0) * (double(W) / H) * t * r + (1.0 - 2.0 * (j + 0.5) / H) * t * u).normalized();
}

// Pixel coordinates of a world point through the OpenGL matrices (window y flipped to rows).
Vec<2> throughMatrices(const Camera& cam, const Vec<3>& x, double n, double fa) {
  const Eigen::Vector4d clip = cam.projectionMatrix(n, fa) * cam.viewMatrix() * Eigen::Vector4d(x.x(), x.y(), x.z(), 1.0);
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  CHECK(ndc.z() > -1.0);
  CHECK(ndc.z() < 1.0);
  return Vec<2>(0.5 * (ndc.x() + 1.0) * cam.width(), 0.5 * (1.0 - ndc.y()) * cam.height());
}

}  // namespace

TEST_CASE("camera: perspective rays follow the look-at formula") {
  const CameraSpec s = spec(Vec<3>(1, 2, 4), Vec<3>(0.2, -0.1, 0.3), Vec<3>(0.1, 1, 0.2), 37);
  const int W = 9, H = 5;
  const Camera cam(s, Projection::Perspective, W, H, 1.5);
  const Vec<3> f = (Vec<3>(0.2, -0.1, 0.3) - Vec<3>(1, 2, 4)).normalized();
  // Odd sizes: the centre pixel looks along f.
  CHECK((cam.pixelRay(4, 2).direction - f).norm() < 1e-14);
  for (auto [i, j] : {std::pair{0, 0}, {W - 1, 0}, {0, H - 1}, {W - 1, H - 1}, {3, 1}}) {
    const Ray ray = cam.pixelRay(i, j);
    CHECK((ray.origin - Vec<3>(1, 2, 4)).norm() == 0.0);
    CHECK((ray.direction - formulaDirection(s, W, H, i, j)).norm() < 1e-14);
  }
  // Row 0 is the top: its rays point more along u than the bottom row's.
  CHECK(cam.pixelRay(4, 0).direction.dot(cam.up()) > cam.pixelRay(4, H - 1).direction.dot(cam.up()));
  CHECK(cam.pixelRay(W - 1, 2).direction.dot(cam.right()) > 0);
  CHECK(std::abs(cam.right().dot(cam.up())) < 1e-15);
  CHECK(std::abs(cam.up().dot(cam.forward())) < 1e-15);
}

TEST_CASE("camera: orthographic rays are parallel with the §4 origins") {
  const CameraSpec s = spec(Vec<3>(0, 0, 4), Vec<3>(0, 0, 0), Vec<3>(0, 1, 0), 40);
  const int W = 8, H = 4;
  const double h = 1.25;
  const Camera cam(s, Projection::Orthographic, W, H, h);
  for (auto [i, j] : {std::pair{0, 0}, {7, 3}, {2, 1}}) {
    const Ray ray = cam.pixelRay(i, j);
    CHECK((ray.direction - Vec<3>(0, 0, -1)).norm() < 1e-15);
    const Vec<3> expected(
        (2.0 * (i + 0.5) / W - 1.0) * (double(W) / H) * h, (1.0 - 2.0 * (j + 0.5) / H) * h, 4.0);
    CHECK((ray.origin - expected).norm() < 1e-14);
  }
}

TEST_CASE("camera: view/projection matrices and project() map ray points back to the pixel centre") {
  const CameraSpec s = spec(Vec<3>(2, 1.5, 3), Vec<3>(0, 0.1, 0), Vec<3>(0, 1, 0), 45);
  for (Projection proj : {Projection::Perspective, Projection::Orthographic}) {
    const Camera cam(s, proj, 64, 48, 1.3);
    Box<3> box;
    box.lo = Vec<3>::Constant(-1.2);
    box.hi = Vec<3>::Constant(1.2);
    const Eigen::Vector2d nf = cam.depthRange(box);
    CHECK(nf.x() < nf.y());
    for (auto [i, j] : {std::pair{0, 0}, {63, 47}, {10, 30}, {32, 24}}) {
      const Ray ray = cam.pixelRay(i, j);
      for (double t : {2.5, 3.5, 4.5}) {
        const Vec<3> x = ray.at(t);
        const Vec<2> p = throughMatrices(cam, x, 0.5, 10.0);
        CHECK(std::abs(p.x() - (i + 0.5)) < 1e-9);
        CHECK(std::abs(p.y() - (j + 0.5)) < 1e-9);
        const Vec<2> q = cam.project(x);
        CHECK(std::abs(q.x() - (i + 0.5)) < 1e-9);
        CHECK(std::abs(q.y() - (j + 0.5)) < 1e-9);
      }
    }
  }
}

TEST_CASE("camera: invalid specs are InputErrors") {
  CHECK_THROWS_AS(Camera(spec(Vec<3>(0, 0, 1), Vec<3>(0, 0, 1), Vec<3>(0, 1, 0), 40), Projection::Perspective, 8, 8, 1),
                  InputError);
  CHECK_THROWS_AS(Camera(spec(Vec<3>(0, 0, 4), Vec<3>(0, 0, 0), Vec<3>(0, 0, 1), 40), Projection::Perspective, 8, 8, 1),
                  InputError);
  CHECK_THROWS_AS(Camera(spec(Vec<3>(0, 0, 4), Vec<3>(0, 0, 0), Vec<3>(0, 1, 0), 180), Projection::Perspective, 8, 8, 1),
                  InputError);
  CHECK_THROWS_AS(Camera(spec(Vec<3>(0, 0, 4), Vec<3>(0, 0, 0), Vec<3>(0, 1, 0), 40), Projection::Orthographic, 8, 0, 1),
                  InputError);
  CHECK_THROWS_AS(Camera(spec(Vec<3>(0, 0, 4), Vec<3>(0, 0, 0), Vec<3>(0, 1, 0), 40), Projection::Orthographic, 8, 8, 0),
                  InputError);
  ViewSpec v;
  CHECK_NOTHROW(Camera(v.camera, v.projection, v.size[0], v.size[1], v.halfHeight2d));
}

TEST_CASE("camera: 2D view mapping (centre ± half_height, square pixels, row 0 = largest y)") {
  const View2d view(Vec<2>(0.5, -1.0), 2.0, 40, 20);
  CHECK(view.pixelSize() == doctest::Approx(0.2));
  const Box<2> b = view.visibleBox();
  CHECK(b.lo.y() == doctest::Approx(-3.0));
  CHECK(b.hi.y() == doctest::Approx(1.0));
  CHECK(b.lo.x() == doctest::Approx(0.5 - 4.0));
  CHECK(b.hi.x() == doctest::Approx(0.5 + 4.0));
  CHECK(view.pixelCenter(0, 0).y() > view.pixelCenter(0, 19).y());
  CHECK((view.pixelCenter(0, 0) - Vec<2>(-3.4, 0.9)).norm() < 1e-12);
  const Vec<2> p = view.worldToPixel(Vec<2>(1.234, -0.77));
  CHECK((view.pixelToWorld(p.x(), p.y()) - Vec<2>(1.234, -0.77)).norm() < 1e-12);
  const Eigen::Vector4d lo = view.projectionMatrix() * Eigen::Vector4d(b.lo.x(), b.lo.y(), 0, 1);
  const Eigen::Vector4d hi = view.projectionMatrix() * Eigen::Vector4d(b.hi.x(), b.hi.y(), 0, 1);
  CHECK(lo.x() == doctest::Approx(-1));
  CHECK(lo.y() == doctest::Approx(-1));
  CHECK(hi.x() == doctest::Approx(1));
  CHECK(hi.y() == doctest::Approx(1));
  CHECK_THROWS_AS(View2d(Vec<2>(0, 0), -1.0, 4, 4), InputError);
}
