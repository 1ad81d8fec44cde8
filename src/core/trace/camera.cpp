#include "core/trace/camera.h"

#include <algorithm>
#include <limits>
#include <cmath>
#include <string>

#include "core/base/errors.h"

namespace hermite {

namespace {

Vec<3> toVec(const std::array<double, 3>& a) { return Vec<3>(a[0], a[1], a[2]); }

void checkSize(int width, int height) {
  if (width < 1 || height < 1)
    throw InputError("view.size: must be at least 1×1 (got " + std::to_string(width) + "×" +
                     std::to_string(height) + ")");
}

void checkHalfHeight(double h) {
  if (!(std::isfinite(h) && h > 0))
    throw InputError("view.view2d.half_height: must be finite and > 0 (got " + std::to_string(h) + ")");
}

}  // namespace

Camera::Camera(const CameraSpec& spec, Projection projection, int width, int height, double halfHeight)
    : projection_(projection), width_(width), height_(height), halfHeight_(halfHeight) {
  checkSize(width, height);
  checkHalfHeight(halfHeight);
  eye_ = toVec(spec.eye);
  const Vec<3> target = toVec(spec.target);
  const Vec<3> up = toVec(spec.up);
  if (!eye_.allFinite()) throw InputError("view.camera.eye: must be finite");
  if (!target.allFinite()) throw InputError("view.camera.target: must be finite");
  if (!up.allFinite()) throw InputError("view.camera.up: must be finite");
  const Vec<3> d = target - eye_;
  if (!(d.norm() > 0)) throw InputError("view.camera: eye and target must differ");
  f_ = d.normalized();
  const Vec<3> side = f_.cross(up);
  // Relative test: up within ~1e-9 rad of the view direction gives no usable right axis.
  if (!(side.norm() > 1e-9 * up.norm()))
    throw InputError("view.camera.up: must not be zero or parallel to target − eye");
  r_ = side.normalized();
  u_ = r_.cross(f_);
  if (!(spec.fovYDeg > 0 && spec.fovYDeg < 180))
    throw InputError("view.camera.fov_y_deg: must be in (0, 180) (got " + std::to_string(spec.fovYDeg) + ")");
  tanHalf_ = std::tan(0.5 * spec.fovYDeg * M_PI / 180.0);
}

Ray Camera::ray(double px, double py) const {
  const double a = 2.0 * px / width_ - 1.0;   // −1 at the left edge, +1 at the right
  const double b = 1.0 - 2.0 * py / height_;  // +1 at the top edge, −1 at the bottom
  Ray ray;
  if (projection_ == Projection::Perspective) {
    ray.origin = eye_;
    ray.direction = (f_ + (a * aspect() * tanHalf_) * r_ + (b * tanHalf_) * u_).normalized();
  } else {
    ray.origin = eye_ + (a * aspect() * halfHeight_) * r_ + (b * halfHeight_) * u_;
    ray.direction = f_;
  }
  return ray;
}

std::optional<Vec<2>> Camera::projectVisible(const Vec<3>& x) const {
  if (projection_ == Projection::Perspective && (x - eye_).dot(f_) <= 0) return std::nullopt;
  return project(x);
}

Vec<2> Camera::project(const Vec<3>& x) const {
  const Vec<3> d = x - eye_;
  const double cx = r_.dot(d), cy = u_.dot(d), cz = f_.dot(d);
  double a, b;
  if (projection_ == Projection::Perspective) {
    a = cx / (cz * tanHalf_ * aspect());
    b = cy / (cz * tanHalf_);
  } else {
    a = cx / (halfHeight_ * aspect());
    b = cy / halfHeight_;
  }
  return Vec<2>(0.5 * (a + 1.0) * width_, 0.5 * (1.0 - b) * height_);
}

Eigen::Matrix4d Camera::viewMatrix() const {
  Eigen::Matrix4d V = Eigen::Matrix4d::Identity();
  V.block<1, 3>(0, 0) = r_.transpose();
  V.block<1, 3>(1, 0) = u_.transpose();
  V.block<1, 3>(2, 0) = -f_.transpose();
  V(0, 3) = -r_.dot(eye_);
  V(1, 3) = -u_.dot(eye_);
  V(2, 3) = f_.dot(eye_);
  return V;
}

Eigen::Matrix4d Camera::projectionMatrix(double nearPlane, double farPlane) const {
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  const double n = nearPlane, fa = farPlane;
  if (projection_ == Projection::Perspective) {
    P(0, 0) = 1.0 / (tanHalf_ * aspect());
    P(1, 1) = 1.0 / tanHalf_;
    P(2, 2) = (fa + n) / (n - fa);
    P(2, 3) = 2.0 * fa * n / (n - fa);
    P(3, 2) = -1.0;
  } else {
    P(0, 0) = 1.0 / (halfHeight_ * aspect());
    P(1, 1) = 1.0 / halfHeight_;
    P(2, 2) = -2.0 / (fa - n);
    P(2, 3) = -(fa + n) / (fa - n);
    P(3, 3) = 1.0;
  }
  return P;
}

Eigen::Vector2d Camera::depthRange(const Box<3>& box) const {
  double lo = INFINITY, hi = -INFINITY;
  for (int c = 0; c < 8; ++c) {
    const Vec<3> corner((c & 1) ? box.hi.x() : box.lo.x(), (c & 2) ? box.hi.y() : box.lo.y(),
                        (c & 4) ? box.hi.z() : box.lo.z());
    const double z = f_.dot(corner - eye_);
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  const double pad = 0.01 * box.extent().norm() + 1e-12;
  lo -= pad;
  hi += pad;
  if (projection_ == Projection::Perspective) {
    hi = std::max(hi, 1e-6);
    lo = std::max(lo, 1e-4 * hi);
  }
  return Eigen::Vector2d(lo, hi);
}

View2d::View2d(const Vec<2>& center, double halfHeight, int width, int height)
    : center_(center), halfHeight_(halfHeight), width_(width), height_(height) {
  checkSize(width, height);
  checkHalfHeight(halfHeight);
  if (!center.allFinite()) throw InputError("view.view2d.center: must be finite");
}

Vec<2> View2d::pixelToWorld(double px, double py) const {
  const double s = pixelSize();
  return Vec<2>(center_.x() + (px - 0.5 * width_) * s, center_.y() + (0.5 * height_ - py) * s);
}

Vec<2> View2d::worldToPixel(const Vec<2>& x) const {
  const double s = pixelSize();
  return Vec<2>((x.x() - center_.x()) / s + 0.5 * width_, 0.5 * height_ - (x.y() - center_.y()) / s);
}

Eigen::Matrix4d View2d::projectionMatrix() const {
  const double halfWidth = halfHeight_ * double(width_) / height_;
  Eigen::Matrix4d P = Eigen::Matrix4d::Identity();
  P(0, 0) = 1.0 / halfWidth;
  P(0, 3) = -center_.x() / halfWidth;
  P(1, 1) = 1.0 / halfHeight_;
  P(1, 3) = -center_.y() / halfHeight_;
  return P;
}

Box<2> View2d::visibleBox() const {
  Box<2> b;
  b.lo = pixelToWorld(0, height_);
  b.hi = pixelToWorld(width_, 0);
  return b;
}

bool clipRayToBox(const Ray& ray, const Box<3>& box, double& t0, double& t1) {
  t0 = 0.0;
  t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double o = ray.origin(k), d = ray.direction(k);
    if (d == 0) {
      if (o < box.lo(k) || o > box.hi(k)) return false;
      continue;
    }
    double ta = (box.lo(k) - o) / d, tb = (box.hi(k) - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

}  // namespace hermite
