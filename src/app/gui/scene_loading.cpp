#include "app/gui/scene_loading.h"

#include <algorithm>

#include "app/gui/camera_framing.h"
#include "app/gui/demo_scene.h"
#include "scene/data_file_scene.h"

namespace hermite::app {

namespace {

bool overridesKey(const std::vector<std::string>& overrides, const std::string& prefix) {
  return std::any_of(overrides.begin(), overrides.end(), [&](const std::string& o) { return o.rfind(prefix, 0) == 0; });
}

// The view of `scene` framing `box` (2·Dim numbers, min then max): the 3D camera moved back
// along its direction, or the 2D centre and half height with 25 % room.
void frameBox(Scene& scene, const std::vector<double>& box) {
  const double aspect = double(scene.view.size[0]) / scene.view.size[1];
  if (scene.dimension() == 2) {
    const double w = box[2] - box[0], h = box[3] - box[1];
    scene.view.center2d = {0.5 * (box[0] + box[2]), 0.5 * (box[1] + box[3])};
    const double half = 0.5 * 1.25 * std::max(h, w / aspect);
    if (half > 0) scene.view.halfHeight2d = half;
    return;
  }
  ShownBox shown;
  shown.box.lo = Vec<3>(box[0], box[1], box[2]);
  shown.box.hi = Vec<3>(box[3], box[4], box[5]);
  if (!(shown.box.extent().norm() > 0)) return;
  const FramedCamera f = framedCamera(scene.view.camera, shown, aspect);
  scene.view.camera = f.camera;
  scene.view.halfHeight2d = f.halfHeight;
}

}  // namespace

DataFileScene loadDataFileScene(const std::string& path, const std::vector<std::string>& overrides) {
  DataFileScene d = dataFileScene(path, overrides);
  if (!overridesKey(overrides, "view.camera") && !overridesKey(overrides, "view.view2d"))
    frameBox(d.scene, d.samplesBox);
  return d;
}

Scene loadCommandScene(const SceneArgs& args) {
  if (!args.scenePath.empty()) {
    if (isSceneFilePath(args.scenePath)) return loadSceneFile(args.scenePath, args.overrides);
    return loadDataFileScene(args.scenePath, args.overrides).scene;
  }
  nlohmann::json doc = nlohmann::json::parse(kDemoSceneJson);
  for (const std::string& o : args.overrides) applySetOverride(doc, o);
  return parseScene(doc, "<demo scene>", ".");
}

}  // namespace hermite::app
