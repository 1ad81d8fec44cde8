#include "app/tools/transform_gizmo.h"

#include <imgui.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

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
std::optional<Vec<2>> TransformGizmo::worldToView(const Vec<3>& x) const {
  if (ctx_.dimension() == 2) return sceneView2d(ctx_.scene(), ctx_.view.w, ctx_.view.h).worldToPixel(x.head<2>());
  return sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h).projectVisible(x);
}

// Pivot (the transformed centroid) and the gizmo's size in world units; false without a fit.
bool TransformGizmo::frame(Vec<3>& pivot, double& size) const {
  const FitOutcome* f = ctx_.fits.shown().get();
  if (!f) return false;
  return f->visitImplicit([&](const auto& fit) {
    constexpr int D = std::decay_t<decltype(fit)>::kDim;
    pivot = Vec<3>::Zero();
    pivot.head<D>() = fit.data.points.rowwise().mean();
    size = 0.2 * viewBounds<D>(ctx_.scene().view, fit.data.points).extent().norm();
  });
}

std::vector<TransformGizmo::Handle> TransformGizmo::handles() const {
  std::vector<Handle> out;
  Vec<3> pivot;
  double size;
  if (!ctx_.showGizmo || !frame(pivot, size)) return out;
  const int dim = ctx_.dimension();
  for (int a = 0; a < dim; ++a) out.push_back({Handle::Translate, a});
  if (dim == 2) out.push_back({Handle::Rotate, 2});
  else
    for (int a = 0; a < 3; ++a) out.push_back({Handle::Rotate, a});
  out.push_back({Handle::Scale, 0});
  return out;
}

// Screen polyline of a handle (arrow: 2 points; ring: kRingSegments + 1; scale: 1 point).
std::vector<Vec<2>> TransformGizmo::shape(const Handle& h) const {
  std::vector<Vec<2>> pts;
  Vec<3> pivot;
  double size;
  if (!frame(pivot, size)) return pts;
  const auto add = [&](const Vec<3>& x) {
    if (const auto p = worldToView(x)) pts.push_back(*p);
  };
  switch (h.kind) {
    case Handle::Translate:
      add(pivot);
      add(pivot + size * Vec<3>::Unit(h.axis));
      break;
    case Handle::Rotate: {
      const Vec<3> axis = Vec<3>::Unit(h.axis);
      const Vec<3> u = axis.unitOrthogonal(), v = axis.cross(u);
      for (int k = 0; k <= kRingSegments; ++k) {
        const double a = 2 * M_PI * k / kRingSegments;
        add(pivot + 0.8 * size * (std::cos(a) * u + std::sin(a) * v));
      }
      break;
    }
    case Handle::Scale:
      if (const auto p = worldToView(pivot)) pts.push_back(*p + Vec<2>(28, 28));  // beside the pivot
      break;
  }
  return pts;
}

std::optional<TransformGizmo::Handle> TransformGizmo::pick(const Vec<2>& mouse) const {
  std::optional<Handle> best;
  double bestD = kPickPx;
  for (const Handle& h : handles()) {
    const std::vector<Vec<2>> pts = shape(h);
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

void TransformGizmo::drag(const Vec<2>& mouse) {
  Vec<3> pivot;
  double size;
  if (!frame(pivot, size)) return;
  const Vec<2> delta = mouse - lastMouse_;
  const Vec<2> previous = lastMouse_;
  lastMouse_ = mouse;
  if (delta.norm() == 0) return;
  const int dim = ctx_.dimension();
  Scene s = ctx_.scene();
  Pose p = poseOf(s.transform, dim);
  switch (grabbed_.kind) {
    case Handle::Translate: {
      // Along the axis by the mouse motion projected on the axis's screen direction.
      const std::vector<Vec<2>> pts = shape(grabbed_);
      if (pts.size() < 2) return;
      const Vec<2> screenAxis = pts[1] - pts[0];
      const double len2 = screenAxis.squaredNorm();
      if (len2 < 4) return;  // the axis points at the eye
      p.t += (delta.dot(screenAxis) / len2) * size * Vec<3>::Unit(grabbed_.axis);
      break;
    }
    case Handle::Rotate: {
      const auto centre = worldToView(pivot);
      if (!centre) return;
      const Vec<2> a = previous - *centre, b = mouse - *centre;
      double angle = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // screen angle, y down
      // Screen y points down: a clockwise-looking screen turn is counter-clockwise in the world
      // when the axis faces the viewer.
      double facing = 1;
      if (dim == 3) facing = Vec<3>::Unit(grabbed_.axis).dot(-sceneCamera(s, ctx_.view.w, ctx_.view.h).forward()) >= 0 ? 1 : -1;
      angle = -angle * facing;
      const Mat<3> dR = Eigen::AngleAxisd(angle, Vec<3>::Unit(grabbed_.axis)).toRotationMatrix();
      p.R = dR * p.R;
      p.t = dR * (p.t - pivot) + pivot;  // about the pivot
      break;
    }
    case Handle::Scale: {
      const double factor = std::exp((delta.x() - delta.y()) / 150.0);
      p.q *= factor;
      p.t = factor * (p.t - pivot) + pivot;
      break;
    }
  }
  setPose(s.transform, p, dim);
  ctx_.document.update(s);
}

bool TransformGizmo::press(const Vec<2>& mouse) {
  const auto h = pick(mouse);
  if (!h) return false;
  grabbed_ = *h;
  lastMouse_ = mouse;
  static const char* names[] = {"translate", "rotate", "scale"};
  ctx_.document.begin(std::string(names[int(h->kind)]) + " (gizmo)");
  ctx_.setStatus(std::string("gizmo: ") + names[int(h->kind)]);
  return true;
}

void TransformGizmo::draw() const {
  const Vec<2> o = ctx_.view.origin();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const auto hovered = ctx_.drag == Drag::Gizmo ? std::optional<Handle>(grabbed_)
                                            : pick(Vec<2>(mouse.x - o.x(), mouse.y - o.y()));
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImU32 axisColour[3] = {IM_COL32(220, 50, 40, 255), IM_COL32(40, 170, 60, 255), IM_COL32(50, 90, 230, 255)};
  for (const Handle& h : handles()) {
    const std::vector<Vec<2>> pts = shape(h);
    const bool hot = hovered && hovered->kind == h.kind && hovered->axis == h.axis;
    const float w = hot ? 4.0f : 2.5f;
    const ImU32 c = h.kind == Handle::Scale ? IM_COL32(240, 200, 40, 255) : axisColour[h.axis];
    if (h.kind == Handle::Scale && pts.size() == 1) {
      const ImVec2 p(float(pts[0].x() + o.x()), float(pts[0].y() + o.y()));
      dl->AddRectFilled(ImVec2(p.x - 5, p.y - 5), ImVec2(p.x + 5, p.y + 5), c);
      if (hot) dl->AddRect(ImVec2(p.x - 7, p.y - 7), ImVec2(p.x + 7, p.y + 7), IM_COL32(255, 255, 255, 255));
      continue;
    }
    std::vector<ImVec2> line;
    for (const Vec<2>& p : pts) line.emplace_back(float(p.x() + o.x()), float(p.y() + o.y()));
    if (line.size() >= 2) dl->AddPolyline(line.data(), int(line.size()), c, ImDrawFlags_None, w);
    if (h.kind == Handle::Translate && line.size() == 2) {
      // Arrow head.
      const Vec<2> d = (pts[1] - pts[0]).normalized(), n(-d.y(), d.x());
      const Vec<2> tip = pts[1] + o, l = tip - 10 * d + 5 * n, r = tip - 10 * d - 5 * n;
      dl->AddTriangleFilled(line[1], ImVec2(float(l.x()), float(l.y())), ImVec2(float(r.x()), float(r.y())), c);
    }
  }
}

}  // namespace hermite::app
