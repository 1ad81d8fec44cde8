#pragma once
// Cameras (docs/maths.md, Conventions): the 3D look-at camera (perspective or orthographic) whose pixel rays
// every tracer shares, its OpenGL view/projection matrices, and the 2D view mapping.
//
// Pixels: column i ∈ [0, W), row j ∈ [0, H), row 0 = top. Continuous pixel coordinates (px, py)
// put the centre of pixel (i, j) at (i + ½, j + ½).

#include <array>
#include <optional>

#include <Eigen/Core>

#include "core/base/geometry.h"

namespace hermite {

enum class Projection { Perspective, Orthographic };

// The look-at parameters of a 3D camera (the scene key `view.camera`).
struct CameraSpec {
  std::array<double, 3> eye{0, 0, 4};
  std::array<double, 3> target{0, 0, 0};
  std::array<double, 3> up{0, 1, 0};
  double fovYDeg = 40.0;  // (0, 180)
  bool operator==(const CameraSpec&) const = default;
};


struct Ray {
  Vec<3> origin = Vec<3>::Zero();
  Vec<3> direction = Vec<3>::UnitZ();  // unit length
  Vec<3> at(double t) const { return origin + t * direction; }
};

// [t0, t1] of the ray inside the box, t ≥ 0 (slab test); false when the ray misses it.
bool clipRayToBox(const Ray& ray, const Box<3>& box, double& t0, double& t1);

// Right-handed look-at camera: f = normalize(target − eye), r = normalize(f × up), u = r × f,
// t = tan(fov_y/2). Perspective ray of pixel (i, j): origin eye, direction
// normalize(f + (2(i+½)/W − 1)(W/H)t·r + (1 − 2(j+½)/H)t·u). Orthographic: direction f, origin
// eye + (2(i+½)/W − 1)(W/H)h·r + (1 − 2(j+½)/H)h·u with h = halfHeight (view2d.half_height).
class Camera {
 public:
  // Throws InputError (naming the view key) for a non-finite eye/target/up, eye = target, up
  // parallel to the view direction, fov_y outside (0, 180), a size < 1, halfHeight ≤ 0.
  Camera(const CameraSpec& spec, Projection projection, int width, int height, double halfHeight);

  // Ray through continuous pixel coordinates (px, py); pixelRay(i, j) = ray(i + ½, j + ½).
  Ray ray(double px, double py) const;
  Ray pixelRay(int i, int j) const { return ray(i + 0.5, j + 0.5); }

  // Continuous pixel coordinates (px, py) of a world point (inverse of ray()); for perspective
  // the point must be in front of the eye (dot(x − eye, f) > 0).
  Vec<2> project(const Vec<3>& x) const;
  // project(x), or none when a perspective camera has x behind (or at) its eye.
  std::optional<Vec<2>> projectVisible(const Vec<3>& x) const;

  // OpenGL matrices consistent with the rays: clip = P·V·x; NDC (x, y) ∈ [−1, 1]² maps to
  // window (px, H − py), i.e. glViewport(0, 0, W, H) with rows flipped (GL row 0 = bottom).
  // View: world → camera space (x = r, y = u, −z = f), the origin at the eye.
  Eigen::Matrix4d viewMatrix() const;
  // Perspective: gluPerspective(fov_y, W/H, near, far) (0 < near < far). Orthographic:
  // glOrtho(−(W/H)h, (W/H)h, −h, h, near, far) (near < far; near may be ≤ 0).
  Eigen::Matrix4d projectionMatrix(double nearPlane, double farPlane) const;
  // A [near, far] range along f that contains the box (padded by 1 % of its diagonal);
  // perspective near is clamped to ≥ 1e-4·far.
  Eigen::Vector2d depthRange(const Box<3>& box) const;

  const Vec<3>& eye() const { return eye_; }
  const Vec<3>& forward() const { return f_; }
  const Vec<3>& right() const { return r_; }
  const Vec<3>& up() const { return u_; }
  Projection projection() const { return projection_; }
  int width() const { return width_; }
  int height() const { return height_; }
  double aspect() const { return double(width_) / height_; }  // W/H
  double tanHalfFov() const { return tanHalf_; }
  double halfHeight() const { return halfHeight_; }  // orthographic scale, world units

 private:
  Vec<3> eye_, f_, r_, u_;
  Projection projection_;
  int width_, height_;
  double tanHalf_;
  double halfHeight_;
};

// The 2D field view: centre ± halfHeight vertically, square pixels, row 0 = the
// largest y. Pixel size s = 2·halfHeight/H world units.
class View2d {
 public:
  // Throws InputError for a size < 1, halfHeight ≤ 0 or a non-finite centre.
  View2d(const Vec<2>& center, double halfHeight, int width, int height);

  // World point of continuous pixel coordinates: x = cx + (px − W/2)s, y = cy + (H/2 − py)s.
  Vec<2> pixelToWorld(double px, double py) const;
  Vec<2> pixelCenter(int i, int j) const { return pixelToWorld(i + 0.5, j + 0.5); }
  Vec<2> worldToPixel(const Vec<2>& x) const;
  // World → NDC (x, y) ∈ [−1, 1]² with +y up, as a 4×4 OpenGL matrix (z passes through).
  Eigen::Matrix4d projectionMatrix() const;
  // The world rectangle the view shows.
  Box<2> visibleBox() const;

  double pixelSize() const { return 2.0 * halfHeight_ / height_; }
  const Vec<2>& center() const { return center_; }
  double halfHeight() const { return halfHeight_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Vec<2> center_;
  double halfHeight_;
  int width_, height_;
};

}  // namespace hermite
