#include "app/gui/scene_loading.h"

#include "app/gui/demo_scene.h"

namespace hermite::app {

Scene loadCommandScene(const SceneArgs& args) {
  if (!args.scenePath.empty()) return loadSceneFile(args.scenePath, args.overrides);
  nlohmann::json doc = nlohmann::json::parse(kDemoSceneJson);
  for (const std::string& o : args.overrides) applySetOverride(doc, o);
  return parseScene(doc, "<demo scene>", ".");
}

}  // namespace hermite::app
