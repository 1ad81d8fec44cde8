#include "app/tools/camera_tool.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "app/gui/camera_framing.h"
#include "app/tools/spec_vectors.h"
#include "scene/view_bounds.h"

namespace hermite::app {

void CameraTool::orbit(double dx, double dy) {
  const ViewSpec& v = ctx_.scene().view;
  CameraSpec c = v.camera;
  const Vec<3> target = toVec(c.target), up = toVec(c.up).normalized();
  Vec<3> offset = toVec(c.eye) - target;
  const double yaw = -dx * 0.008, pitch = -dy * 0.008;
  offset = Eigen::AngleAxisd(yaw, up) * offset;
  const Vec<3> right = (-offset).cross(up).normalized();
  const Vec<3> pitched = Eigen::AngleAxisd(pitch, right) * offset;
  // Stop short of the poles: the look-at camera needs up not parallel to the view direction.
  if (std::abs(pitched.normalized().dot(up)) < 0.995) offset = pitched;
  c.eye = toArray(target + offset);
  ctx_.document.setCamera(c, v.center2d, v.halfHeight2d);
}

void CameraTool::pan(double dx, double dy) {
  const ViewSpec& v = ctx_.scene().view;
  if (ctx_.dimension() == 2) {
    const double s = 2.0 * v.halfHeight2d / ctx_.view.h;
    ctx_.document.setCamera(v.camera, {v.center2d[0] - dx * s, v.center2d[1] + dy * s}, v.halfHeight2d);
    return;
  }
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  const double dist = (toVec(v.camera.target) - cam.eye()).norm();
  const double s = (cam.projection() == Projection::Perspective ? 2.0 * dist * cam.tanHalfFov() : 2.0 * cam.halfHeight()) / ctx_.view.h;
  const Vec<3> shift = -dx * s * cam.right() + dy * s * cam.up();
  CameraSpec c = v.camera;
  c.eye = toArray(toVec(c.eye) + shift);
  c.target = toArray(toVec(c.target) + shift);
  ctx_.document.setCamera(c, v.center2d, v.halfHeight2d);
}

void CameraTool::zoom(double notches, const Vec<2>& mouse) {
  const double s = std::pow(0.85, notches);
  const ViewSpec& v = ctx_.scene().view;
  if (ctx_.dimension() == 2) {
    const View2d view = sceneView2d(ctx_.scene(), ctx_.view.w, ctx_.view.h);
    const Vec<2> x = view.pixelToWorld(mouse.x(), mouse.y());
    const Vec<2> c = x + s * (Vec<2>(v.center2d[0], v.center2d[1]) - x);
    ctx_.document.setCamera(v.camera, {c.x(), c.y()}, v.halfHeight2d * s);
    return;
  }
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  CameraSpec c = v.camera;
  // The point under the cursor at the target's depth stays under the cursor.
  const Ray ray = cam.ray(mouse.x(), mouse.y());
  const Vec<3> target = toVec(c.target);
  const double t = (target - ray.origin).dot(cam.forward()) / std::max(ray.direction.dot(cam.forward()), 1e-9);
  const Vec<3> x = ray.at(t);
  if (cam.projection() == Projection::Perspective) {
    c.eye = toArray(x + s * (toVec(c.eye) - x));
    c.target = toArray(x + s * (target - x));
    ctx_.document.setCamera(c, v.center2d, v.halfHeight2d);
  } else {
    const Vec<3> shift = (1 - s) * (x - target);
    c.eye = toArray(toVec(c.eye) + shift);
    c.target = toArray(target + shift);
    ctx_.document.setCamera(c, v.center2d, v.halfHeight2d * s);
  }
}

// 2D: the samples' box; 3D: what the mode shows (camera_framing.h), seen along the current direction.
void CameraTool::fitToView() {
  const FitOutcome* shown = ctx_.fits.shown().get();
  if (!shown) return;
  const ViewSpec& v = ctx_.scene().view;
  const double aspect = double(ctx_.view.primaryWidth()) / ctx_.view.h;  // the left half when comparing
  if (const auto* f2 = shown->as<SceneFit<2>>()) {
    const Box<2> b = samplesBox<2>(v, f2->data.points);
    const Vec<2> c = b.center();
    ctx_.document.setCamera(v.camera, {c.x(), c.y()}, 0.5 * std::max(b.extent().y(), b.extent().x() / aspect) * 1.05);
    return;
  }
  const std::optional<ShownBox> box = shownBox3d(*shown);
  if (!box) return;
  const FramedCamera f = framedCamera(v.camera, *box, aspect);
  ctx_.document.setCamera(f.camera, v.center2d, f.halfHeight);
}

void CameraTool::resetView() {
  ctx_.document.setCamera(ctx_.home.camera, ctx_.home.center, ctx_.home.halfHeight);
}

}  // namespace hermite::app
