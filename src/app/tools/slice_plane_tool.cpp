#include "app/tools/slice_plane_tool.h"

#include <algorithm>
#include <cmath>

#include "app/tools/spec_vectors.h"
#include "scene/view_bounds.h"

namespace hermite::app {

double sliceOffsetExtent(const GuiContext& ctx) {
  const ViewSpec& v = ctx.scene().view;
  const SceneFit<3>* f3 = ctx.fits.shown() ? ctx.fits.shown()->as<SceneFit<3>>() : nullptr;
  if (!f3) return 2.0;
  const Box<3> b = viewBounds<3>(v, f3->data.points);
  const Vec<3> n = toVec(v.slice.normal).normalized();
  // ± the farthest corner along the normal.
  return std::max(n.cwiseAbs().dot(b.lo.cwiseAbs().cwiseMax(b.hi.cwiseAbs())), 1e-6);
}

// Parameter s of the point of the line grab + s·n nearest to the mouse ray (closest points of
// two lines); none when the normal is within ~1° of the ray, where s is ill-conditioned.
std::optional<double> SlicePlaneTool::lineParameter(const Vec<2>& mouse) const {
  const Ray ray = sceneCamera(ctx_.scene(), ctx_.view.primaryWidth(), ctx_.view.h).ray(mouse.x(), mouse.y());
  const Vec<3> n = toVec(ctx_.scene().view.slice.normal).normalized();
  const double b = n.dot(ray.direction);
  const double denom = 1.0 - b * b;
  if (denom < 3e-4) return std::nullopt;
  const Vec<3> w0 = grab_.point - ray.origin;
  return (b * ray.direction.dot(w0) - n.dot(w0)) / denom;
}

bool SlicePlaneTool::press(const Vec<2>& mouse) {
  const SliceSpec& slice = ctx_.scene().view.slice;
  if (ctx_.scene().mode != SceneMode::Implicit3d || !slice.enabled || !ctx_.fits.shown() || !ctx_.fits.shown()->as<SceneFit<3>>()) return false;
  const Vec<3> n = toVec(slice.normal).normalized();
  if (!n.allFinite()) return false;
  const Ray ray = sceneCamera(ctx_.scene(), ctx_.view.primaryWidth(), ctx_.view.h).ray(mouse.x(), mouse.y());
  // The plane point under the cursor, or else the bounds centre's foot on the plane.
  const double denom = n.dot(ray.direction);
  const double t = std::abs(denom) > 1e-12 ? (slice.offset - n.dot(ray.origin)) / denom : -1.0;
  const Vec<3> centre = viewBounds<3>(ctx_.scene().view, ctx_.fits.shown()->as<SceneFit<3>>()->data.points).center();
  grab_.point = t > 0 ? ray.at(t) : Vec<3>(centre + (slice.offset - n.dot(centre)) * n);
  grab_.offset = slice.offset;
  grab_.lineParameter = lineParameter(mouse);
  grab_.pressY = mouse.y();
  ctx_.document.begin("move slice plane");
  ctx_.setStatus("moving the slice plane along its normal");
  return true;
}

void SlicePlaneTool::drag(const Vec<2>& mouse) {
  const std::optional<double> s = lineParameter(mouse);
  const double extent = sliceOffsetExtent(ctx_);
  double offset;
  if (s && grab_.lineParameter) {
    offset = grab_.offset + (*s - *grab_.lineParameter);
  } else {
    // Normal along the view ray: moving up the screen raises the offset, the view's height
    // being one bounds diagonal.
    const double diagonal = 2.0 * std::sqrt(3.0) * extent;
    offset = grab_.offset + (grab_.pressY - mouse.y()) * diagonal / std::max(ctx_.view.h, 1);
  }
  offset = std::clamp(offset, -extent, extent);
  if (offset == ctx_.scene().view.slice.offset) return;
  Scene next = ctx_.scene();
  next.view.slice.offset = offset;
  ctx_.document.update(next);
}

}  // namespace hermite::app
