#include "app/tools/sample_tool.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app/tools/spec_vectors.h"
#include "core/trace/field2d_reference.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"

namespace hermite::app {

namespace {

constexpr double kPickRadiusPx = 9.0;
constexpr double kNormalLength3d = 0.05;  // of the bounds diagonal, as the tracer draws normals

// The tip of sample i's normal as the 3D view draws it (world units).
Vec<3> normalTip3d(const Scene& scene, const SceneFit<3>& fit, int i) {
  const Box<3> b = viewBounds<3>(scene.view, fit.data.points);
  return fit.data.points.col(i) + kNormalLength3d * b.extent().norm() * fit.data.normals.col(i).normalized();
}

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

std::optional<Vec<2>> SampleTool::samplePosition(int i) const { return position(i, false); }

std::optional<Vec<2>> SampleTool::normalTipPosition(int i) const { return position(i, true); }

std::optional<Vec<2>> SampleTool::position(int i, bool tip) const {
  const FitOutcome* f = ctx_.fits.shown().get();
  if (!f || i < 0 || i >= f->dataCount()) return std::nullopt;
  const int w = ctx_.view.primaryWidth();
  if (const auto* f2 = f->as<SceneFit<2>>()) {
    const Vec<2> p = sceneView2d(ctx_.scene(), w, ctx_.view.h).worldToPixel(f2->data.points.col(i));
    if (!tip) return p;
    const Vec<2> n = f2->data.normals.col(i).normalized();
    return Vec<2>(p + Field2dStyle{}.normalLengthPx * Vec<2>(n.x(), -n.y()));
  }
  const SceneFit<3>& f3 = *f->as<SceneFit<3>>();
  const Vec<3> p = tip ? normalTip3d(ctx_.scene(), f3, i) : Vec<3>(f3.data.points.col(i));
  return sceneCamera(ctx_.scene(), w, ctx_.view.h).projectVisible(p);
}

int SampleTool::pick(const Vec<2>& mouse, bool* onTip) const {
  *onTip = false;
  // The selected sample's normal tip first: it sits on top of other points.
  if (ctx_.selected >= 0) {
    const auto tip = normalTipPosition(ctx_.selected);
    if (tip && (*tip - mouse).norm() <= kPickRadiusPx) {
      *onTip = true;
      return ctx_.selected;
    }
  }
  const FitOutcome* f = ctx_.fits.shown().get();
  if (!f) return -1;
  const int n = f->dataCount();
  int best = -1;
  double bestD = kPickRadiusPx;
  for (int i = 0; i < n; ++i) {
    const auto p = samplePosition(i);
    if (!p) continue;
    const double d = (*p - mouse).norm();
    if (d <= bestD) {
      bestD = d;
      best = i;
    }
  }
  return best;
}

int SampleTool::sampleAt(const Vec<2>& mouse) const {
  bool tip = false;
  return pick(mouse, &tip);
}

bool SampleTool::press(const Vec<2>& mouse, bool anySample) {
  bool tip = false;
  const int hit = pick(mouse, &tip);
  if (hit < 0 || (!anySample && hit != ctx_.selected)) return false;
  ctx_.selected = hit;
  ctx_.drag = tip ? Drag::NormalTip : Drag::Sample;
  if (const SceneFit<3>* f3 = ctx_.dimension() == 3 && ctx_.fits.shown() ? ctx_.fits.shown()->as<SceneFit<3>>() : nullptr) {
    dragPlanePoint_ = tip ? normalTip3d(ctx_.scene(), *f3, hit) : Vec<3>(f3->data.points.col(hit));
  }
  ctx_.document.begin(tip ? "rotate normal" : "move sample");
  {
    std::vector<std::string> warnings;  // those of the data: the fits report them
    ctx_.fits.worker().prepareDrag(ctx_.dimension() == 2 ? withInlineSamples<2>(ctx_.scene(), warnings)
                                                        : withInlineSamples<3>(ctx_.scene(), warnings),
                                   hit);
  }
  ctx_.setStatus((tip ? "rotating the normal of sample " : "moving sample ") + std::to_string(hit));
  return true;
}

void SampleTool::drag(const Vec<2>& mouse) { move(mouse, ctx_.drag == Drag::NormalTip); }

// The document's samples become inline (the first edit of a preset or file scene) and the
// displayed data is what the fit interpolates: edits apply to the data before the scene's
// transform, so the inverse transform maps screen positions back.
void SampleTool::move(const Vec<2>& mouse, bool tip) {
  if (ctx_.selected < 0 || !ctx_.fits.shown()) return;
  if (ctx_.dimension() == 2)
    moveTo<2>(tip, [&](const Scene& s) -> std::optional<Vec<2>> {
      return sceneView2d(s, ctx_.view.primaryWidth(), ctx_.view.h).pixelToWorld(mouse.x(), mouse.y());
    });
  else
    moveTo<3>(tip, [&](const Scene& s) -> std::optional<Vec<3>> {
      // On the plane through the grabbed point (or tip) facing the camera.
      const Camera cam = sceneCamera(s, ctx_.view.primaryWidth(), ctx_.view.h);
      const Ray ray = cam.ray(mouse.x(), mouse.y());
      const double denom = ray.direction.dot(cam.forward());
      if (std::abs(denom) < 1e-12) return std::nullopt;
      const double t = (dragPlanePoint_ - ray.origin).dot(cam.forward()) / denom;
      if (!(t > 0)) return std::nullopt;
      return ray.at(t);
    });
}

// The selected sample (tip: its normal, towards the point) moves to where `target` says, in
// world units of the transformed view; nothing when it says none.
template <int Dim, class Target>
void SampleTool::moveTo(bool tip, Target target) {
  std::vector<std::string> warnings;
  Scene s = withInlineSamples<Dim>(ctx_.scene(), warnings);
  HermiteSamples<Dim> d = inlineSamples<Dim>(s);
  if (ctx_.selected >= d.size()) return;
  const std::optional<Vec<Dim>> shown = target(s);
  if (!shown) return;
  const Vec<Dim> world = sceneSimilarity<Dim>(s.transform).applyInverse(*shown);
  if (tip) {
    const Vec<Dim> dir = world - d.points.col(ctx_.selected);
    if (dir.norm() < 1e-12) return;
    d.normals.col(ctx_.selected) = dir.normalized();
  } else {
    d.points.col(ctx_.selected) = world;
  }
  setInlineSamples<Dim>(s, d);
  ctx_.document.update(s);
}

void SampleTool::addAt(const Vec<2>& mouse) {
  const FitOutcome* fit = ctx_.currentFit();
  if (!fit) return;
  std::vector<std::string> warnings;
  const int w = ctx_.view.primaryWidth();
  if (ctx_.dimension() == 2) {
    Scene s = withInlineSamples<2>(ctx_.scene(), warnings);
    HermiteSamples<2> d = inlineSamples<2>(s);
    const Vec<2> x = sceneView2d(s, w, ctx_.view.h).pixelToWorld(mouse.x(), mouse.y());
    Vec<2> n = fit->as<SceneFit<2>>()->field().gradient(x);
    n = n.norm() > 1e-12 ? Vec<2>(n.normalized()) : Vec<2>(0, 1);
    const Similarity<2> T = sceneSimilarity<2>(s.transform);
    d.points.conservativeResize(2, d.size() + 1);
    d.normals.conservativeResize(2, d.points.cols());
    d.points.col(d.size() - 1) = T.applyInverse(x);
    d.normals.col(d.size() - 1) = T.R.transpose() * n;
    setInlineSamples<2>(s, d);
    ctx_.document.apply(s, "add sample");
    ctx_.selected = d.size() - 1;
    ctx_.setStatus("added sample " + std::to_string(ctx_.selected));
    return;
  }
  addAt3d(mouse, *fit);
}

// 3D: on the surface (the traced depth under the cursor) or else on the slice plane.
void SampleTool::addAt3d(const Vec<2>& mouse, const FitOutcome& fit) {
  std::vector<std::string> warnings;
  const int w = ctx_.view.primaryWidth();
  const Camera cam = sceneCamera(ctx_.scene(), w, ctx_.view.h);
  const Ray ray = cam.ray(mouse.x(), mouse.y());
  std::optional<Vec<3>> hit;
  const int rw = ctx_.image.result().width, rh = ctx_.image.result().height;
  if (rw > 0 && !ctx_.image.result().depth.empty()) {
    const int i = std::clamp(int(mouse.x() * rw / w), 0, rw - 1), j = std::clamp(int(mouse.y() * rh / ctx_.view.h), 0, rh - 1);
    const float depth = ctx_.image.result().depth[std::size_t(j) * rw + i];
    if (std::isfinite(depth)) hit = ray.at(depth);
  }
  const SliceSpec& slice = ctx_.scene().view.slice;
  if (!hit && slice.enabled) {
    const Vec<3> n = toVec(slice.normal).normalized();
    const double denom = n.dot(ray.direction);
    if (std::abs(denom) > 1e-12) {
      const double t = (slice.offset - n.dot(ray.origin)) / denom;
      if (t > 0) hit = ray.at(t);
    }
  }
  if (!hit) {
    ctx_.setStatus("Ctrl+click on the surface or on the slice plane to add a sample", true);
    return;
  }
  Scene s = withInlineSamples<3>(ctx_.scene(), warnings);
  HermiteSamples<3> d = inlineSamples<3>(s);
  Vec<3> n = fit.as<SceneFit<3>>()->field().gradient(*hit);
  n = n.norm() > 1e-12 ? Vec<3>(n.normalized()) : Vec<3>(-ray.direction);
  const Similarity<3> T = sceneSimilarity<3>(s.transform);
  d.points.conservativeResize(3, d.size() + 1);
  d.normals.conservativeResize(3, d.points.cols());
  d.points.col(d.size() - 1) = T.applyInverse(*hit);
  d.normals.col(d.size() - 1) = T.R.transpose() * n;
  setInlineSamples<3>(s, d);
  ctx_.document.apply(s, "add sample");
  ctx_.selected = d.size() - 1;
  ctx_.setStatus("added sample " + std::to_string(ctx_.selected));
}

void SampleTool::deleteSelected() {
  if (ctx_.selected < 0) return;
  const FitOutcome* fit = ctx_.currentFit();
  if (!fit) return;
  const int n = fit->dataCount();
  if (n <= 1) {
    ctx_.setStatus("cannot delete the last sample", true);
    return;
  }
  const Scene s = ctx_.dimension() == 2 ? editSample<2>(ctx_.scene(), ctx_.selected, true) : editSample<3>(ctx_.scene(), ctx_.selected, true);
  ctx_.document.apply(s, "delete sample");
  ctx_.setStatus("deleted sample " + std::to_string(ctx_.selected));
  ctx_.selected = -1;
}

void SampleTool::flipSelected() {
  if (ctx_.selected < 0) return;
  const Scene s = ctx_.dimension() == 2 ? editSample<2>(ctx_.scene(), ctx_.selected, false) : editSample<3>(ctx_.scene(), ctx_.selected, false);
  ctx_.document.apply(s, "flip normal");
  ctx_.setStatus("flipped the normal of sample " + std::to_string(ctx_.selected));
}

void SampleTool::drawSelection() const {
  if (ctx_.selected < 0) return;
  ImDrawList* fg = ImGui::GetBackgroundDrawList();
  auto p = samplePosition(ctx_.selected);
  auto tip = normalTipPosition(ctx_.selected);
  if (!p) return;
  *p += ctx_.view.origin();
  if (tip) *tip += ctx_.view.origin();
  fg->AddCircle(ImVec2(float(p->x()), float(p->y())), 7.0f, IM_COL32(255, 200, 0, 255), 16, 2.5f);
  if (tip) {
    fg->AddLine(ImVec2(float(p->x()), float(p->y())), ImVec2(float(tip->x()), float(tip->y())), IM_COL32(255, 200, 0, 255), 2.0f);
    fg->AddCircleFilled(ImVec2(float(tip->x()), float(tip->y())), 5.0f, IM_COL32(255, 200, 0, 255));
  }
}

}  // namespace hermite::app
