#pragma once
// Loads the scene of a command: a file with its --set overrides, or the built-in demo scene.

#include "app/commands/commands.h"
#include "scene/scene_file.h"

namespace hermite::app {

Scene loadCommandScene(const SceneArgs& args);

}  // namespace hermite::app
