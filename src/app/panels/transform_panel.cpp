// Transforming the fitted implicit without re-solving: the Transform panel (numeric
// fields, the update / re-solve switch with both times and their difference, non-uniform scale
// by composition) and the gizmo drawn with ImGui draw lists — translate arrows along the world
// axes, rotation rings about them, a uniform-scale handle — acting about the pivot (the
// transformed centroid of the samples). Every drag is one undo step.

#include <imgui.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "app/gui/gui_app.h"
#include "app/gui/gui_widgets.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"

namespace hermite::app {

namespace {

constexpr int kRingSegments = 64;
constexpr double kPickPx = 7.0;

// The scene's similarity as (R, q, t) in 3D (2D rotations embedded about z).
struct Pose {
  Mat<3> R = Mat<3>::Identity();
  double q = 1;
  Vec<3> t = Vec<3>::Zero();
};

Pose poseOf(const TransformSpec& s, int dim) {
  Pose p;
  p.q = s.scale;
  for (int k = 0; k < dim && k < int(s.translate.size()); ++k) p.t(k) = s.translate[std::size_t(k)];
  if (dim == 2) {
    p.R = Eigen::AngleAxisd(s.rotateDeg * M_PI / 180, Vec<3>::UnitZ()).toRotationMatrix();
  } else {
    const Vec<3> axis(s.rotateAxisAngleDeg[0], s.rotateAxisAngleDeg[1], s.rotateAxisAngleDeg[2]);
    if (axis.norm() > 0) p.R = Eigen::AngleAxisd(s.rotateAxisAngleDeg[3] * M_PI / 180, axis.normalized()).toRotationMatrix();
  }
  return p;
}

void setPose(TransformSpec& s, const Pose& p, int dim) {
  s.scale = p.q;
  s.translate.assign(std::size_t(dim), 0.0);
  for (int k = 0; k < dim; ++k) s.translate[std::size_t(k)] = p.t(k);
  if (dim == 2) {
    s.rotateDeg = std::atan2(p.R(1, 0), p.R(0, 0)) * 180 / M_PI;
  } else {
    const Eigen::AngleAxisd aa(p.R);
    const Vec<3> axis = aa.angle() == 0 ? Vec<3>::UnitZ() : Vec<3>(aa.axis());
    s.rotateAxisAngleDeg = {axis.x(), axis.y(), axis.z(), aa.angle() * 180 / M_PI};
  }
}

}  // namespace

// The view's mapping of world points to view pixels (2D points have z = 0).
std::optional<Vec<2>> GuiApp::worldToView(const Vec<3>& x) const {
  if (dimension() == 2) return sceneView2d(scene(), viewW_, viewH_).worldToPixel(x.head<2>());
  const Camera cam = sceneCamera(scene(), viewW_, viewH_);
  if (cam.projection() == Projection::Perspective && (x - cam.eye()).dot(cam.forward()) <= 0) return std::nullopt;
  return cam.project(x);
}

// Pivot (the transformed centroid) and the gizmo's size in world units; false without a fit.
bool GuiApp::gizmoFrame(Vec<3>& pivot, double& size) const {
  const FitOutcome* f = shown_.get();
  if (!f) return false;
  if (f->fit3) {
    pivot = f->fit3->data.points.rowwise().mean();
    size = 0.2 * viewBounds<3>(scene().view, f->fit3->data.points).extent().norm();
    return true;
  }
  if (f->fit2) {
    pivot = Vec<3>::Zero();
    pivot.head<2>() = f->fit2->data.points.rowwise().mean();
    size = 0.2 * viewBounds<2>(scene().view, f->fit2->data.points).extent().norm();
    return true;
  }
  return false;
}

std::vector<GuiApp::GizmoHandle> GuiApp::gizmoHandles() const {
  std::vector<GizmoHandle> out;
  Vec<3> pivot;
  double size;
  if (!showGizmo_ || !gizmoFrame(pivot, size)) return out;
  const int dim = dimension();
  for (int a = 0; a < dim; ++a) out.push_back({GizmoHandle::Translate, a});
  if (dim == 2) out.push_back({GizmoHandle::Rotate, 2});
  else
    for (int a = 0; a < 3; ++a) out.push_back({GizmoHandle::Rotate, a});
  out.push_back({GizmoHandle::Scale, 0});
  return out;
}

// Screen polyline of a handle (arrow: 2 points; ring: kRingSegments + 1; scale: 1 point).
std::vector<Vec<2>> GuiApp::gizmoShape(const GizmoHandle& h) const {
  std::vector<Vec<2>> pts;
  Vec<3> pivot;
  double size;
  if (!gizmoFrame(pivot, size)) return pts;
  const auto add = [&](const Vec<3>& x) {
    if (const auto p = worldToView(x)) pts.push_back(*p);
  };
  switch (h.kind) {
    case GizmoHandle::Translate:
      add(pivot);
      add(pivot + size * Vec<3>::Unit(h.axis));
      break;
    case GizmoHandle::Rotate: {
      const Vec<3> axis = Vec<3>::Unit(h.axis);
      const Vec<3> u = axis.unitOrthogonal(), v = axis.cross(u);
      for (int k = 0; k <= kRingSegments; ++k) {
        const double a = 2 * M_PI * k / kRingSegments;
        add(pivot + 0.8 * size * (std::cos(a) * u + std::sin(a) * v));
      }
      break;
    }
    case GizmoHandle::Scale:
      if (const auto p = worldToView(pivot)) pts.push_back(*p + Vec<2>(28, 28));  // beside the pivot
      break;
  }
  return pts;
}

std::optional<GuiApp::GizmoHandle> GuiApp::pickGizmo(const Vec<2>& mouse) const {
  std::optional<GizmoHandle> best;
  double bestD = kPickPx;
  for (const GizmoHandle& h : gizmoHandles()) {
    const std::vector<Vec<2>> pts = gizmoShape(h);
    double d = 1e30;
    if (pts.size() == 1) d = (pts[0] - mouse).norm() - 4.0;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const Vec<2> a = pts[k], b = pts[k + 1];
      const double t = std::clamp((mouse - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12), 0.0, 1.0);
      d = std::min(d, (a + t * (b - a) - mouse).norm());
    }
    if (d < bestD) {
      bestD = d;
      best = h;
    }
  }
  return best;
}

void GuiApp::dragGizmo(const Vec<2>& mouse) {
  Vec<3> pivot;
  double size;
  if (!gizmoFrame(pivot, size)) return;
  const Vec<2> delta = mouse - lastGizmoMouse_;
  const Vec<2> previous = lastGizmoMouse_;
  lastGizmoMouse_ = mouse;
  if (delta.norm() == 0) return;
  const int dim = dimension();
  Scene s = scene();
  Pose p = poseOf(s.transform, dim);
  switch (gizmo_.kind) {
    case GizmoHandle::Translate: {
      // Along the axis by the mouse motion projected on the axis's screen direction.
      const std::vector<Vec<2>> pts = gizmoShape(gizmo_);
      if (pts.size() < 2) return;
      const Vec<2> screenAxis = pts[1] - pts[0];
      const double len2 = screenAxis.squaredNorm();
      if (len2 < 4) return;  // the axis points at the eye
      p.t += (delta.dot(screenAxis) / len2) * size * Vec<3>::Unit(gizmo_.axis);
      break;
    }
    case GizmoHandle::Rotate: {
      const auto centre = worldToView(pivot);
      if (!centre) return;
      const Vec<2> a = previous - *centre, b = mouse - *centre;
      double angle = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // screen angle, y down
      // Screen y points down: a clockwise-looking screen turn is counter-clockwise in the world
      // when the axis faces the viewer.
      double facing = 1;
      if (dim == 3) facing = Vec<3>::Unit(gizmo_.axis).dot(-sceneCamera(s, viewW_, viewH_).forward()) >= 0 ? 1 : -1;
      angle = -angle * facing;
      const Mat<3> dR = Eigen::AngleAxisd(angle, Vec<3>::Unit(gizmo_.axis)).toRotationMatrix();
      p.R = dR * p.R;
      p.t = dR * (p.t - pivot) + pivot;  // about the pivot
      break;
    }
    case GizmoHandle::Scale: {
      const double factor = std::exp((delta.x() - delta.y()) / 150.0);
      p.q *= factor;
      p.t = factor * (p.t - pivot) + pivot;
      break;
    }
  }
  setPose(s.transform, p, dim);
  document_.update(s);
}

bool GuiApp::pressGizmo(const Vec<2>& mouse) {
  const auto h = pickGizmo(mouse);
  if (!h) return false;
  gizmo_ = *h;
  lastGizmoMouse_ = mouse;
  static const char* names[] = {"translate", "rotate", "scale"};
  document_.begin(std::string(names[int(h->kind)]) + " (gizmo)");
  setStatus(std::string("gizmo: ") + names[int(h->kind)]);
  return true;
}

void GuiApp::drawGizmo() {
  const Vec<2> o = viewOrigin();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const auto hovered = drag_ == Drag::Gizmo ? std::optional<GizmoHandle>(gizmo_)
                                            : pickGizmo(Vec<2>(mouse.x - o.x(), mouse.y - o.y()));
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImU32 axisColour[3] = {IM_COL32(220, 50, 40, 255), IM_COL32(40, 170, 60, 255), IM_COL32(50, 90, 230, 255)};
  for (const GizmoHandle& h : gizmoHandles()) {
    const std::vector<Vec<2>> pts = gizmoShape(h);
    const bool hot = hovered && hovered->kind == h.kind && hovered->axis == h.axis;
    const float w = hot ? 4.0f : 2.5f;
    const ImU32 c = h.kind == GizmoHandle::Scale ? IM_COL32(240, 200, 40, 255) : axisColour[h.axis];
    if (h.kind == GizmoHandle::Scale && pts.size() == 1) {
      const ImVec2 p(float(pts[0].x() + o.x()), float(pts[0].y() + o.y()));
      dl->AddRectFilled(ImVec2(p.x - 5, p.y - 5), ImVec2(p.x + 5, p.y + 5), c);
      if (hot) dl->AddRect(ImVec2(p.x - 7, p.y - 7), ImVec2(p.x + 7, p.y + 7), IM_COL32(255, 255, 255, 255));
      continue;
    }
    std::vector<ImVec2> line;
    for (const Vec<2>& p : pts) line.emplace_back(float(p.x() + o.x()), float(p.y() + o.y()));
    if (line.size() >= 2) dl->AddPolyline(line.data(), int(line.size()), c, ImDrawFlags_None, w);
    if (h.kind == GizmoHandle::Translate && line.size() == 2) {
      // Arrow head.
      const Vec<2> d = (pts[1] - pts[0]).normalized(), n(-d.y(), d.x());
      const Vec<2> tip = pts[1] + o, l = tip - 10 * d + 5 * n, r = tip - 10 * d - 5 * n;
      dl->AddTriangleFilled(line[1], ImVec2(float(l.x()), float(l.y())), ImVec2(float(r.x()), float(r.y())), c);
    }
  }
}

void GuiApp::drawTransformPanel() {
  Scene s = scene();
  TransformSpec& t = s.transform;
  const int dim = dimension();
  bool changed = false;
  std::string label = "transform";
  ImGui::Checkbox("gizmo", &showGizmo_);
  helpMarker("Drag the arrows (translate), the rings (rotate) or the yellow square (uniform scale) in the view.");
  double tr[3] = {0, 0, 0};
  for (int k = 0; k < dim && k < int(t.translate.size()); ++k) tr[k] = t.translate[std::size_t(k)];
  if (ImGui::InputScalarN("translate", ImGuiDataType_Double, tr, dim, nullptr, nullptr, "%.4g",
                          ImGuiInputTextFlags_EnterReturnsTrue)) {
    t.translate.assign(tr, tr + dim);
    changed = true;
    label = "translate";
  }
  if (dim == 3) {
    double axis[3] = {t.rotateAxisAngleDeg[0], t.rotateAxisAngleDeg[1], t.rotateAxisAngleDeg[2]};
    if (ImGui::InputScalarN("rotation axis", ImGuiDataType_Double, axis, 3, nullptr, nullptr, "%.3g",
                            ImGuiInputTextFlags_EnterReturnsTrue) &&
        (axis[0] != 0 || axis[1] != 0 || axis[2] != 0)) {
      t.rotateAxisAngleDeg = {axis[0], axis[1], axis[2], t.rotateAxisAngleDeg[3]};
      changed = true;
      label = "rotation axis";
    }
  }
  double angle = dim == 3 ? t.rotateAxisAngleDeg[3] : t.rotateDeg;
  const double lo = -180, hi = 180;
  if (ImGui::SliderScalar("angle (deg)", ImGuiDataType_Double, &angle, &lo, &hi, "%.2f")) {
    if (!document_.inGesture()) document_.begin("rotate");
    Scene n = scene();
    if (dim == 3) n.transform.rotateAxisAngleDeg[3] = angle;
    else n.transform.rotateDeg = angle;
    document_.update(n);
    s = scene();
  }
  if (ImGui::IsItemDeactivated() && document_.inGesture()) document_.end();
  double q = t.scale;
  const double qlo = 0.05, qhi = 20;
  if (ImGui::SliderScalar("scale", ImGuiDataType_Double, &q, &qlo, &qhi, "%.4g", ImGuiSliderFlags_Logarithmic)) {
    if (!document_.inGesture()) document_.begin("scale");
    Scene n = scene();
    n.transform.scale = q;
    document_.update(n);
    s = scene();
  }
  if (ImGui::IsItemDeactivated() && document_.inGesture()) document_.end();
  int method = int(t.method);
  ImGui::TextUnformatted("model");
  ImGui::SameLine();
  ImGui::RadioButton("auto", &method, 0);
  ImGui::SameLine();
  ImGui::RadioButton("update coefficients", &method, 1);
  ImGui::SameLine();
  ImGui::RadioButton("re-solve", &method, 2);
  recordWidget("transform.method");
  if (method != int(t.method)) {
    t.method = TransformMethod(method);
    changed = true;
    label = "transform model";
  }
  // Non-uniform scale: a diagonal transform.matrix (the composition f(T⁻¹x)).
  double diag[3] = {1, 1, 1};
  if (int(t.matrix.size()) == dim * dim)
    for (int k = 0; k < dim; ++k) diag[k] = t.matrix[std::size_t(k * dim + k)];
  if (ImGui::InputScalarN("non-uniform scale", ImGuiDataType_Double, diag, dim, nullptr, nullptr, "%.3g",
                          ImGuiInputTextFlags_EnterReturnsTrue) &&
      diag[0] > 0 && diag[1] > 0 && (dim == 2 || diag[2] > 0)) {
    t.matrix.assign(std::size_t(dim * dim), 0.0);
    for (int k = 0; k < dim; ++k) t.matrix[std::size_t(k * dim + k)] = diag[k];
    if (t.matrixIsIdentity()) t.matrix.clear();
    changed = true;
    label = "non-uniform scale";
  }
  helpMarker("Not a similarity: the field becomes the composition f(T^-1 x), which is NOT the re-solved "
             "interpolant of the transformed data (the Diagnostics show how far it is from one).");
  if (ImGui::Checkbox("verify against a re-solve", &t.verify)) {
    changed = true;
    label = t.verify ? "verify the transform" : "stop verifying the transform";
  }
  helpMarker("Also re-solve on the transformed data and compare the shown field with it on probes "
             "(transform.verify). Costs a whole fit per change.");
  if (ImGui::Button("Reset transform")) {
    const bool verify = t.verify;
    t = TransformSpec{};
    t.translate.assign(std::size_t(dim), 0.0);
    t.verify = verify;
    changed = true;
    label = "reset transform";
  }
  if (changed) document_.apply(s, label);

  const FitOutcome* f = shown_.get();
  const bool transformed = f && ((f->fit2 && f->fit2->transformed) || (f->fit3 && f->fit3->transformed));
  if (transformed) {
    const TransformReport& r = f->fit2 ? f->fit2->transform : f->fit3->transform;
    ImGui::Separator();
    ImGui::Text("shown: %s%s", r.method.c_str(), r.exact ? " (= the re-solve)" : "");
    if (options_.showTimings) ImGui::Text("update %.3f ms", r.updateMs);
    if (r.resolveMs) {
      if (options_.showTimings) ImGui::Text("re-solve %.2f ms", *r.resolveMs);
      ImGui::Text("max |f_update - f_resolve|  %.2e", *r.maxAbsDf);
      ImGui::Text("max |grad difference|       %.2e", *r.maxGradDiff);
    }
    if (r.method == "composition")
      ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "composition f(T^-1 x): not the re-solved interpolant");
  }
}

}  // namespace hermite::app
