#include "app/gui/camera_framing.h"

#include <algorithm>
#include <cmath>

#include "app/tools/spec_vectors.h"
#include "scene/view_bounds.h"

namespace hermite::app {

template <int Dim>
Box<Dim> samplesBox(const ViewSpec& view, const Points<Dim>& points) {
  const Box<Dim> b = boundingBox<Dim>(points);
  return b.extent().maxCoeff() > 0 ? b : viewBounds<Dim>(view, points);
}

template Box<2> samplesBox<2>(const ViewSpec&, const Points<2>&);
template Box<3> samplesBox<3>(const ViewSpec&, const Points<3>&);

std::optional<ShownBox> shownBox3d(const FitOutcome& fit) {
  if (const auto* f3 = fit.as<SceneFit<3>>()) return ShownBox{samplesBox<3>(fit.scene.view, f3->data.points), 1.05};
  if (const auto* patch = fit.as<PatchDisplay>())
    if (patch->mesh.positions.cols() > 0) return ShownBox{boundingBox<3>(patch->mesh.positions), 1.05};
  if (const auto* holefill = fit.as<HoleFillStages>())
    if (holefill->input.vertexCount() > 0) return ShownBox{boundingBox<3>(holefill->input.vertices), 1.05};
  return std::nullopt;
}

FramedCamera framedCamera(const CameraSpec& camera, const ShownBox& shown, double aspect) {
  const double radius = 0.5 * shown.box.extent().norm();
  FramedCamera out{camera, radius * shown.margin};
  const Vec<3> dir = (toVec(camera.eye) - toVec(camera.target)).normalized();
  const double fov = camera.fovYDeg * M_PI / 180;
  const Vec<3> centre = shown.box.center();
  out.camera.target = toArray(centre);
  out.camera.eye = toArray(centre + radius / std::sin(0.5 * fov * std::min(1.0, aspect)) * shown.margin * dir);
  return out;
}

Scene framedOnLoad(Scene scene) {
  if ((scene.mode != SceneMode::Patch && scene.mode != SceneMode::HoleFill) || !(scene.view.camera == CameraSpec{}))
    return scene;
  FitOutcome content;
  content.scene = scene;
  if (scene.mode == SceneMode::Patch) {
    content.result = buildPatchDisplay(scene.patch);
  } else {
    HoleFillSpec holes = scene.holefill;
    holes.stage = HoleFillStage::Holes;  // the input mesh is all the box needs
    content.result = runHoleFillStages(holes);
  }
  const std::optional<ShownBox> shown = shownBox3d(content);
  if (!shown || !(shown->box.extent().norm() > 0)) return scene;
  const FramedCamera f = framedCamera(scene.view.camera, *shown, double(scene.view.size[0]) / scene.view.size[1]);
  scene.view.camera = f.camera;
  scene.view.halfHeight2d = f.halfHeight;
  return scene;
}

}  // namespace hermite::app
