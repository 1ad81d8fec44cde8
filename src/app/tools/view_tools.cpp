// Direct manipulation in the view: camera (orbit, pan, zoom towards the cursor, fit
// to view, reset) and samples (select, drag, rotate the normal by its tip, flip, add, delete),
// plus the keyboard shortcuts. Nothing here reacts while ImGui wants the mouse / keyboard.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <Eigen/Geometry>
#include <cmath>

#include "app/gui/gui_app.h"
#include "core/base/errors.h"
#include "core/trace/field2d_reference.h"
#include "io/point_file.h"
#include "scene/scene_file.h"
#include "scene/view_bounds.h"

namespace hermite::app {

namespace {

constexpr double kPickRadiusPx = 9.0;
constexpr double kNormalLength3d = 0.05;  // of the bounds diagonal, as the tracer draws normals

bool pressed(const FrameInput& in, const std::array<bool, 512>& prev, int key) { return in.keysDown[key] && !prev[key]; }

Vec<3> toVec(const std::array<double, 3>& a) { return Vec<3>(a[0], a[1], a[2]); }
std::array<double, 3> toArray(const Vec<3>& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

// ---- picking -------------------------------------------------------------------------------

std::optional<Vec<2>> GuiApp::sampleScreenPosition(int i) const {
  const FitOutcome* f = shown_.get();
  if (!f || i < 0) return std::nullopt;
  const int w = primaryViewWidth();
  if (f->fit2) {
    if (i >= f->fit2->data.size()) return std::nullopt;
    return sceneView2d(scene(), w, viewH_).worldToPixel(f->fit2->data.points.col(i));
  }
  if (f->fit3) {
    if (i >= f->fit3->data.size()) return std::nullopt;
    const Camera cam = sceneCamera(scene(), w, viewH_);
    const Vec<3> p = f->fit3->data.points.col(i);
    if (cam.projection() == Projection::Perspective && (p - cam.eye()).dot(cam.forward()) <= 0) return std::nullopt;
    return cam.project(p);
  }
  return std::nullopt;
}

std::optional<Vec<2>> GuiApp::normalTipScreenPosition(int i) const {
  const FitOutcome* f = shown_.get();
  if (!f || i < 0) return std::nullopt;
  const int w = primaryViewWidth();
  if (f->fit2) {
    if (i >= f->fit2->data.size()) return std::nullopt;
    const Vec<2> p = sceneView2d(scene(), w, viewH_).worldToPixel(f->fit2->data.points.col(i));
    const Vec<2> n = f->fit2->data.normals.col(i).normalized();
    return Vec<2>(p + Field2dStyle{}.normalLengthPx * Vec<2>(n.x(), -n.y()));
  }
  if (f->fit3) {
    if (i >= f->fit3->data.size()) return std::nullopt;
    const Box<3> b = viewBounds<3>(scene().view, f->fit3->data.points);
    const Vec<3> tip = f->fit3->data.points.col(i) + kNormalLength3d * b.extent().norm() * f->fit3->data.normals.col(i).normalized();
    const Camera cam = sceneCamera(scene(), w, viewH_);
    if (cam.projection() == Projection::Perspective && (tip - cam.eye()).dot(cam.forward()) <= 0) return std::nullopt;
    return cam.project(tip);
  }
  return std::nullopt;
}

int GuiApp::pickSample(const Vec<2>& mouse, bool* onTip) const {
  *onTip = false;
  // The selected sample's normal tip first: it sits on top of other points.
  if (selected_ >= 0) {
    const auto tip = normalTipScreenPosition(selected_);
    if (tip && (*tip - mouse).norm() <= kPickRadiusPx) {
      *onTip = true;
      return selected_;
    }
  }
  const FitOutcome* f = shown_.get();
  if (!f) return -1;
  const int n = f->fit2 ? f->fit2->data.size() : f->fit3 ? f->fit3->data.size() : 0;
  int best = -1;
  double bestD = kPickRadiusPx;
  for (int i = 0; i < n; ++i) {
    const auto p = sampleScreenPosition(i);
    if (!p) continue;
    const double d = (*p - mouse).norm();
    if (d <= bestD) {
      bestD = d;
      best = i;
    }
  }
  return best;
}

// ---- sample edits ----------------------------------------------------------------------------

// The document's samples become inline (the first edit of a preset or file scene) and the
// displayed data is what the fit interpolates: edits apply to the data before the scene's
// transform, so the inverse transform maps screen positions back.
void GuiApp::moveSelected(const Vec<2>& mouse, bool tip) {
  if (selected_ < 0 || !shown_) return;
  std::vector<std::string> warnings;
  const int w = primaryViewWidth();
  if (dimension() == 2) {
    Scene s = withInlineSamples<2>(scene(), warnings);
    HermiteSamples<2> d = inlineSamples<2>(s);
    if (selected_ >= d.size()) return;
    const Similarity<2> T = sceneSimilarity<2>(s.transform);
    const Vec<2> world = T.applyInverse(sceneView2d(s, w, viewH_).pixelToWorld(mouse.x(), mouse.y()));
    if (tip) {
      const Vec<2> dir = world - d.points.col(selected_);
      if (dir.norm() < 1e-12) return;
      d.normals.col(selected_) = dir.normalized();
    } else {
      d.points.col(selected_) = world;
    }
    setInlineSamples<2>(s, d);
    document_.update(s);
    return;
  }
  Scene s = withInlineSamples<3>(scene(), warnings);
  HermiteSamples<3> d = inlineSamples<3>(s);
  if (selected_ >= d.size()) return;
  const Camera cam = sceneCamera(s, w, viewH_);
  const Ray ray = cam.ray(mouse.x(), mouse.y());
  // The plane through the grabbed point (or tip) facing the camera.
  const double denom = ray.direction.dot(cam.forward());
  if (std::abs(denom) < 1e-12) return;
  const double t = (dragPlanePoint_ - ray.origin).dot(cam.forward()) / denom;
  if (!(t > 0)) return;
  const Similarity<3> T = sceneSimilarity<3>(s.transform);
  const Vec<3> world = T.applyInverse(ray.at(t));
  if (tip) {
    const Vec<3> dir = world - d.points.col(selected_);
    if (dir.norm() < 1e-12) return;
    d.normals.col(selected_) = dir.normalized();
  } else {
    d.points.col(selected_) = world;
  }
  setInlineSamples<3>(s, d);
  document_.update(s);
}

void GuiApp::addSampleAt(const Vec<2>& mouse) {
  const FitOutcome* fit = currentFit();
  if (!fit) return;
  std::vector<std::string> warnings;
  const int w = primaryViewWidth();
  if (dimension() == 2) {
    Scene s = withInlineSamples<2>(scene(), warnings);
    HermiteSamples<2> d = inlineSamples<2>(s);
    const Vec<2> x = sceneView2d(s, w, viewH_).pixelToWorld(mouse.x(), mouse.y());
    Vec<2> n = fit->fit2->field().gradient(x);
    n = n.norm() > 1e-12 ? Vec<2>(n.normalized()) : Vec<2>(0, 1);
    const Similarity<2> T = sceneSimilarity<2>(s.transform);
    d.points.conservativeResize(2, d.size() + 1);
    d.normals.conservativeResize(2, d.points.cols());
    d.points.col(d.size() - 1) = T.applyInverse(x);
    d.normals.col(d.size() - 1) = T.R.transpose() * n;
    setInlineSamples<2>(s, d);
    document_.apply(s, "add sample");
    selected_ = d.size() - 1;
    setStatus("added sample " + std::to_string(selected_));
    return;
  }
  const Camera cam = sceneCamera(scene(), w, viewH_);
  const Ray ray = cam.ray(mouse.x(), mouse.y());
  // On the surface (the traced depth under the cursor) or else on the slice plane.
  std::optional<Vec<3>> hit;
  const int rw = view_.width, rh = view_.height;
  if (rw > 0 && !view_.depth.empty()) {
    const int i = std::clamp(int(mouse.x() * rw / w), 0, rw - 1), j = std::clamp(int(mouse.y() * rh / viewH_), 0, rh - 1);
    const float depth = view_.depth[std::size_t(j) * rw + i];
    if (std::isfinite(depth)) hit = ray.at(depth);
  }
  const SliceSpec& slice = scene().view.slice;
  if (!hit && slice.enabled) {
    const Vec<3> n = toVec(slice.normal).normalized();
    const double denom = n.dot(ray.direction);
    if (std::abs(denom) > 1e-12) {
      const double t = (slice.offset - n.dot(ray.origin)) / denom;
      if (t > 0) hit = ray.at(t);
    }
  }
  if (!hit) {
    setStatus("Ctrl+click on the surface or on the slice plane to add a sample", true);
    return;
  }
  Scene s = withInlineSamples<3>(scene(), warnings);
  HermiteSamples<3> d = inlineSamples<3>(s);
  Vec<3> n = fit->fit3->field().gradient(*hit);
  n = n.norm() > 1e-12 ? Vec<3>(n.normalized()) : Vec<3>(-ray.direction);
  const Similarity<3> T = sceneSimilarity<3>(s.transform);
  d.points.conservativeResize(3, d.size() + 1);
  d.normals.conservativeResize(3, d.points.cols());
  d.points.col(d.size() - 1) = T.applyInverse(*hit);
  d.normals.col(d.size() - 1) = T.R.transpose() * n;
  setInlineSamples<3>(s, d);
  document_.apply(s, "add sample");
  selected_ = d.size() - 1;
  setStatus("added sample " + std::to_string(selected_));
}

namespace {

template <int Dim>
Scene editSample(const Scene& scene, int index, bool remove) {
  std::vector<std::string> warnings;
  Scene s = withInlineSamples<Dim>(scene, warnings);
  HermiteSamples<Dim> d = inlineSamples<Dim>(s);
  if (index < 0 || index >= d.size()) return scene;
  if (remove) {
    HermiteSamples<Dim> r;
    r.points.resize(Dim, d.size() - 1);
    r.normals.resize(Dim, d.size() - 1);
    for (int j = 0, k = 0; j < d.size(); ++j)
      if (j != index) {
        r.points.col(k) = d.points.col(j);
        r.normals.col(k++) = d.normals.col(j);
      }
    d = std::move(r);
  } else {
    d.normals.col(index) = -d.normals.col(index);
  }
  setInlineSamples<Dim>(s, d);
  return s;
}

}  // namespace

void GuiApp::deleteSelected() {
  if (selected_ < 0) return;
  const FitOutcome* fit = currentFit();
  if (!fit) return;
  const int n = fit->fit2 ? fit->fit2->data.size() : fit->fit3->data.size();
  if (n <= 1) {
    setStatus("cannot delete the last sample", true);
    return;
  }
  const Scene s = dimension() == 2 ? editSample<2>(scene(), selected_, true) : editSample<3>(scene(), selected_, true);
  document_.apply(s, "delete sample");
  setStatus("deleted sample " + std::to_string(selected_));
  selected_ = -1;
}

void GuiApp::flipSelected() {
  if (selected_ < 0) return;
  const Scene s = dimension() == 2 ? editSample<2>(scene(), selected_, false) : editSample<3>(scene(), selected_, false);
  document_.apply(s, "flip normal");
  setStatus("flipped the normal of sample " + std::to_string(selected_));
}

// ---- camera ------------------------------------------------------------------------------------

void GuiApp::orbit(double dx, double dy) {
  const ViewSpec& v = scene().view;
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
  document_.setCamera(c, v.center2d, v.halfHeight2d);
}

void GuiApp::pan(double dx, double dy) {
  const ViewSpec& v = scene().view;
  if (dimension() == 2) {
    const double s = 2.0 * v.halfHeight2d / viewH_;
    document_.setCamera(v.camera, {v.center2d[0] - dx * s, v.center2d[1] + dy * s}, v.halfHeight2d);
    return;
  }
  const Camera cam = sceneCamera(scene(), viewW_, viewH_);
  const double dist = (toVec(v.camera.target) - cam.eye()).norm();
  const double s = (cam.projection() == Projection::Perspective ? 2.0 * dist * cam.tanHalfFov() : 2.0 * cam.halfHeight()) / viewH_;
  const Vec<3> shift = -dx * s * cam.right() + dy * s * cam.up();
  CameraSpec c = v.camera;
  c.eye = toArray(toVec(c.eye) + shift);
  c.target = toArray(toVec(c.target) + shift);
  document_.setCamera(c, v.center2d, v.halfHeight2d);
}

void GuiApp::zoom(double notches, const Vec<2>& mouse) {
  const double s = std::pow(0.85, notches);
  const ViewSpec& v = scene().view;
  if (dimension() == 2) {
    const View2d view = sceneView2d(scene(), viewW_, viewH_);
    const Vec<2> x = view.pixelToWorld(mouse.x(), mouse.y());
    const Vec<2> c = x + s * (Vec<2>(v.center2d[0], v.center2d[1]) - x);
    document_.setCamera(v.camera, {c.x(), c.y()}, v.halfHeight2d * s);
    return;
  }
  const Camera cam = sceneCamera(scene(), viewW_, viewH_);
  CameraSpec c = v.camera;
  // The point under the cursor at the target's depth stays under the cursor.
  const Ray ray = cam.ray(mouse.x(), mouse.y());
  const Vec<3> target = toVec(c.target);
  const double t = (target - ray.origin).dot(cam.forward()) / std::max(ray.direction.dot(cam.forward()), 1e-9);
  const Vec<3> x = ray.at(t);
  if (cam.projection() == Projection::Perspective) {
    c.eye = toArray(x + s * (toVec(c.eye) - x));
    c.target = toArray(x + s * (target - x));
    document_.setCamera(c, v.center2d, v.halfHeight2d);
  } else {
    const Vec<3> shift = (1 - s) * (x - target);
    c.eye = toArray(toVec(c.eye) + shift);
    c.target = toArray(target + shift);
    document_.setCamera(c, v.center2d, v.halfHeight2d * s);
  }
}

void GuiApp::fitToView() {
  if (!shown_) return;
  const ViewSpec& v = scene().view;
  if (shown_->fit2) {
    const Box<2> b = viewBounds<2>(v, shown_->fit2->data.points);
    const Vec<2> c = b.center();
    const double aspect = double(viewW_) / viewH_;
    document_.setCamera(v.camera, {c.x(), c.y()}, 0.5 * std::max(b.extent().y(), b.extent().x() / aspect) * 1.05);
    return;
  }
  // 3D: the box to frame (the view bounds of an implicit, already padded; a mesh's own box, with
  // a little more room) seen along the current direction.
  Box<3> b;
  double margin = 1.02;
  if (shown_->fit3) {
    b = viewBounds<3>(v, shown_->fit3->data.points);
  } else if (shown_->patch) {
    b = boundingBox<3>(shown_->patch->mesh.positions);
    margin = 1.05;
  } else if (shown_->holefill && shown_->holefill->input.vertexCount() > 0) {
    b = boundingBox<3>(shown_->holefill->input.vertices);
    margin = 1.05;
  } else {
    return;
  }
  const double radius = 0.5 * b.extent().norm();
  CameraSpec c = v.camera;
  const Vec<3> dir = (toVec(c.eye) - toVec(c.target)).normalized();
  const double fov = c.fovYDeg * M_PI / 180;
  const double aspect = std::min(1.0, double(viewW_) / viewH_);
  c.target = toArray(b.center());
  c.eye = toArray(b.center() + radius / std::sin(0.5 * fov * aspect) * margin * dir);
  document_.setCamera(c, v.center2d, radius * 1.05);
}

void GuiApp::resetView() {
  document_.setCamera(homeCamera_, homeCenter_, homeHalfHeight_);
}

// ---- input ------------------------------------------------------------------------------------

void GuiApp::handleShortcuts(const FrameInput& in) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;
  const auto& prev = prevKeys_;
  if (in.ctrl && pressed(in, prev, GLFW_KEY_Z)) {
    if (in.shift) {
      if (document_.canRedo()) setStatus("redo: " + document_.redoLabel());
      document_.redo();
    } else {
      if (document_.canUndo()) setStatus("undo: " + document_.undoLabel());
      document_.undo();
    }
    return;
  }
  if (in.ctrl && pressed(in, prev, GLFW_KEY_Y)) {
    if (document_.canRedo()) setStatus("redo: " + document_.redoLabel());
    document_.redo();
    return;
  }
  if (in.ctrl && pressed(in, prev, GLFW_KEY_S)) {
    saveScene(savePath_);
    return;
  }
  if (in.ctrl && pressed(in, prev, GLFW_KEY_Q)) quit_ = true;
  if (pressed(in, prev, GLFW_KEY_F1) || (pressed(in, prev, GLFW_KEY_SLASH) && in.shift)) panels.help = !panels.help;
  if (io.WantCaptureKeyboard) return;
  if (pressed(in, prev, GLFW_KEY_F)) fitToView();
  if (pressed(in, prev, GLFW_KEY_HOME)) resetView();
  if (pressed(in, prev, GLFW_KEY_N)) flipSelected();
  if (pressed(in, prev, GLFW_KEY_DELETE) || pressed(in, prev, GLFW_KEY_BACKSPACE)) deleteSelected();
  if (pressed(in, prev, GLFW_KEY_TAB)) panels.hideUi = !panels.hideUi;
  if (pressed(in, prev, GLFW_KEY_ESCAPE)) selected_ = -1;
  if (pressed(in, prev, GLFW_KEY_F12)) {
    char name[64];
    std::snprintf(name, sizeof name, "/hermite-lab-%03d.png", ++screenshotCounter_);
    requestScreenshot(options_.screenshotDirectory + name, screenshotWithUi_);
  }
}

// ---- the slice plane ---------------------------------------------------------------------------

double GuiApp::sliceOffsetExtent() const {
  const ViewSpec& v = scene().view;
  if (!shown_ || !shown_->fit3) return 2.0;
  const Box<3> b = viewBounds<3>(v, shown_->fit3->data.points);
  const Vec<3> n = toVec(v.slice.normal).normalized();
  // ± the farthest corner along the normal.
  return std::max(n.cwiseAbs().dot(b.lo.cwiseAbs().cwiseMax(b.hi.cwiseAbs())), 1e-6);
}

// Parameter s of the point of the line grab + s·n nearest to the mouse ray (closest points of
// two lines); none when the normal is within ~1° of the ray, where s is ill-conditioned.
std::optional<double> GuiApp::sliceLineParameter(const Vec<2>& mouse) const {
  const Ray ray = sceneCamera(scene(), primaryViewWidth(), viewH_).ray(mouse.x(), mouse.y());
  const Vec<3> n = toVec(scene().view.slice.normal).normalized();
  const double b = n.dot(ray.direction);
  const double denom = 1.0 - b * b;
  if (denom < 3e-4) return std::nullopt;
  const Vec<3> w0 = sliceGrab_.point - ray.origin;
  return (b * ray.direction.dot(w0) - n.dot(w0)) / denom;
}

bool GuiApp::pressSlicePlane(const Vec<2>& mouse) {
  const SliceSpec& slice = scene().view.slice;
  if (scene().mode != SceneMode::Implicit3d || !slice.enabled || !shown_ || !shown_->fit3) return false;
  const Vec<3> n = toVec(slice.normal).normalized();
  if (!n.allFinite()) return false;
  const Ray ray = sceneCamera(scene(), primaryViewWidth(), viewH_).ray(mouse.x(), mouse.y());
  // The plane point under the cursor, or else the bounds centre's foot on the plane.
  const double denom = n.dot(ray.direction);
  const double t = std::abs(denom) > 1e-12 ? (slice.offset - n.dot(ray.origin)) / denom : -1.0;
  const Vec<3> centre = viewBounds<3>(scene().view, shown_->fit3->data.points).center();
  sliceGrab_.point = t > 0 ? ray.at(t) : Vec<3>(centre + (slice.offset - n.dot(centre)) * n);
  sliceGrab_.offset = slice.offset;
  sliceGrab_.lineParameter = sliceLineParameter(mouse);
  sliceGrab_.pressY = mouse.y();
  document_.begin("move slice plane");
  setStatus("moving the slice plane along its normal");
  return true;
}

void GuiApp::dragSlicePlane(const Vec<2>& mouse) {
  const std::optional<double> s = sliceLineParameter(mouse);
  const double extent = sliceOffsetExtent();
  double offset;
  if (s && sliceGrab_.lineParameter) {
    offset = sliceGrab_.offset + (*s - *sliceGrab_.lineParameter);
  } else {
    // Normal along the view ray: moving up the screen raises the offset, the view's height
    // being one bounds diagonal.
    const double diagonal = 2.0 * std::sqrt(3.0) * extent;
    offset = sliceGrab_.offset + (sliceGrab_.pressY - mouse.y()) * diagonal / std::max(viewH_, 1);
  }
  offset = std::clamp(offset, -extent, extent);
  if (offset == scene().view.slice.offset) return;
  Scene next = scene();
  next.view.slice.offset = offset;
  document_.update(next);
}

void GuiApp::handleViewInput(const FrameInput& in) {
  const ImGuiIO& io = ImGui::GetIO();
  const Vec<2> mouse(in.mouseX - viewX_, in.mouseY - viewY_);  // view pixels
  const Vec<2> delta = mouse - lastMouse_;
  lastMouse_ = mouse;
  const bool leftPressed = in.mouseDown[0] && !prevMouseDown_[0];
  const bool anyDown = in.mouseDown[0] || in.mouseDown[1] || in.mouseDown[2];

  // A drag in progress owns the mouse until release, even over a panel.
  if (drag_ != Drag::None) {
    if (!anyDown) {
      if (drag_ == Drag::Sample || drag_ == Drag::NormalTip || drag_ == Drag::PatchHandle || drag_ == Drag::Gizmo ||
          drag_ == Drag::SlicePlane)
        document_.end();
      drag_ = Drag::None;
      return;
    }
    switch (drag_) {
      case Drag::Orbit: orbit(delta.x(), delta.y()); break;
      case Drag::Pan: pan(delta.x(), delta.y()); break;
      case Drag::Sample: moveSelected(mouse, false); break;
      case Drag::NormalTip: moveSelected(mouse, true); break;
      case Drag::PatchHandle: dragPatchHandle(mouse, in); break;
      case Drag::Gizmo: dragGizmo(mouse); break;
      case Drag::SlicePlane: dragSlicePlane(mouse); break;
      case Drag::None: break;
    }
    return;
  }
  if (io.WantCaptureMouse || in.mouseX < 0) return;
  if (mouse.x() < 0 || mouse.y() < 0 || mouse.x() >= viewW_ || mouse.y() >= viewH_) return;
  if (in.wheel != 0) zoom(in.wheel, mouse);

  if (leftPressed && scene().mode == SceneMode::Patch) {
    if (!in.shift && pressPatchHandle(mouse)) {
      drag_ = Drag::PatchHandle;
      return;
    }
    drag_ = in.shift ? Drag::Pan : Drag::Orbit;
    return;
  }
  if (leftPressed && !in.ctrl && !in.shift && showGizmo_ && pressGizmo(mouse)) {
    drag_ = Drag::Gizmo;
    return;
  }
  if (leftPressed && in.alt && !in.ctrl && pressSlicePlane(mouse)) {
    drag_ = Drag::SlicePlane;
    return;
  }
  if (leftPressed && in.ctrl) {
    addSampleAt(mouse);
    return;
  }
  if (leftPressed && !in.shift) {
    bool tip = false;
    const int hit = pickSample(mouse, &tip);
    if (hit >= 0) {
      selected_ = hit;
      drag_ = tip ? Drag::NormalTip : Drag::Sample;
      if (dimension() == 3 && shown_ && shown_->fit3) {
        const Vec<3> p = shown_->fit3->data.points.col(hit);
        const Box<3> b = viewBounds<3>(scene().view, shown_->fit3->data.points);
        dragPlanePoint_ = tip ? Vec<3>(p + kNormalLength3d * b.extent().norm() * shown_->fit3->data.normals.col(hit).normalized()) : p;
      }
      document_.begin(tip ? "rotate normal" : "move sample");
      {
        std::vector<std::string> warnings;  // those of the data: the fits report them
        worker_.prepareDrag(dimension() == 2 ? withInlineSamples<2>(scene(), warnings)
                                             : withInlineSamples<3>(scene(), warnings),
                            hit);
      }
      setStatus((tip ? "rotating the normal of sample " : "moving sample ") + std::to_string(hit));
      return;
    }
    selected_ = -1;
    drag_ = dimension() == 3 ? Drag::Orbit : Drag::Pan;
    return;
  }
  if ((leftPressed && in.shift) || (in.mouseDown[1] && !prevMouseDown_[1]) || (in.mouseDown[2] && !prevMouseDown_[2]))
    drag_ = Drag::Pan;
}

void GuiApp::handleDroppedFiles(const FrameInput& in) {
  if (in.droppedFiles.empty()) return;
  const std::string& path = in.droppedFiles.front();
  if (path.size() > 5 && path.substr(path.size() - 5) == ".json") {
    openScene(path);
    return;
  }
  if (scene().mode == SceneMode::HoleFill) {  // in hole-fill mode a file is the mesh to fill
    openHoleFillMesh(path);
    return;
  }
  // A point file: keep the fit and view settings, replace the data.
  try {
    const int dim = pointFileDimension(path);
    Scene s = scene();
    s.mode = dim == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d;
    s.data = DataSpec{};
    s.data.file = path;
    s.data.resolvedFile = path;
    std::vector<std::string> warnings;
    // Read now, so a malformed file is reported here and not as a failed fit.
    if (dim == 2) sceneSamples<2>(s, warnings);
    else sceneSamples<3>(s, warnings);
    s.view.bounds.reset();
    document_.apply(s, "open " + path);
    selected_ = -1;
    setStatus("loaded " + path);
  } catch (const std::exception& e) {
    setStatus(e.what(), true);
  }
}

}  // namespace hermite::app
