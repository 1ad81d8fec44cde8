#pragma once
// Loads the scene of a command or of the GUI's Open box: a scene file with its --set overrides,
// a data file (point or mesh file) as the default scene around it (scene/data_file_scene.h),
// or the built-in demo scene.

#include <string>
#include <vector>

#include "app/commands/commands.h"
#include "scene/data_file_scene.h"
#include "scene/scene_file.h"

namespace hermite::app {

Scene loadCommandScene(const SceneArgs& args);

// The default scene of a data file with its camera (3D) or 2D view framing the samples, unless
// the overrides set view.camera / view2d themselves.
DataFileScene loadDataFileScene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace hermite::app
