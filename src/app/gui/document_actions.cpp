#include "app/gui/document_actions.h"

#include <filesystem>
#include <memory>

#include "app/gui/camera_framing.h"
#include "app/gui/scene_loading.h"
#include "io/mesh_file.h"
#include "scene/data_file_scene.h"

namespace hermite::app {

void openScene(GuiContext& ctx, const std::string& path) {
  try {
    Scene s = framedOnLoad(loadSceneFile(path));
    ctx.document.reset(s, path);
    ctx.setHomeFromScene();
    ctx.selected = -1;
    ctx.savePath = path;
    ctx.setStatus("opened " + path);
  } catch (const std::exception& e) {
    ctx.setStatus(e.what(), true);
  }
}

namespace {

// A data file (point or mesh file) opens as the default scene around it (scene_loading.h), the
// same scene `hermite-lab FILE` opens; Save proposes FILE's name with .json beside it.
void openDataFile(GuiContext& ctx, const std::string& path) {
  try {
    DataFileScene d = loadDataFileScene(path);
    ctx.document.reset(d.scene, "");
    ctx.setHomeFromScene();
    ctx.selected = -1;
    ctx.savePath = std::filesystem::path(path).replace_extension(".json").string();
    ctx.loadedData = GuiContext::LoadedData{d.scene.data, d.samples, d.spacing, d.warnings,
                                            std::make_shared<const Eigen::MatrixXd>(std::move(d.points))};
    std::string status = "loaded " + path + ": " + std::to_string(d.samples) + " samples (" +
                         std::to_string(d.scene.dimension()) + "D)";
    if (!d.warnings.empty()) status += "; " + d.warnings.front();
    ctx.setStatus(status);
  } catch (const std::exception& e) {
    ctx.setStatus(e.what(), true);
  }
}

}  // namespace

void openFile(GuiContext& ctx, const std::string& path) {
  try {
    if (isSceneFilePath(path))
      openScene(ctx, path);
    else if (ctx.scene().mode == SceneMode::HoleFill && isMeshFileExtension(path))
      openHoleFillMesh(ctx, path);
    else
      openDataFile(ctx, path);
  } catch (const std::exception& e) {
    ctx.setStatus(e.what(), true);
  }
}

void openHoleFillMesh(GuiContext& ctx, const std::string& path) {
  try {
    loadMesh(path);  // read now, so a malformed file is reported here and not as a failed run
    Scene s = ctx.scene();
    s.holefill.mesh = path;
    s.holefill.resolvedMesh = path;
    ctx.document.apply(s, "open " + path);
    ctx.setStatus("loaded " + path + " (the mesh to fill)");
  } catch (const std::exception& e) {
    ctx.setStatus(e.what(), true);
  }
}

void loadPreset(GuiContext& ctx, const std::string& preset, SceneMode mode) {
  Scene s = ctx.scene();
  s.mode = mode;
  s.data = DataSpec{};
  s.data.preset = preset;
  s.view.bounds.reset();
  ctx.document.apply(s, "preset " + preset);
  ctx.selected = -1;
  ctx.setStatus("preset " + preset);
}

void saveScene(GuiContext& ctx, const std::string& path) {
  try {
    ctx.document.save(path);
    ctx.setStatus("saved " + path);
  } catch (const std::exception& e) {
    ctx.setStatus(e.what(), true);
  }
}

void editFit(GuiContext& ctx, const FitSpec& fit, const std::string& label) {
  if (fit == ctx.scene().fit) return;
  Scene s = ctx.scene();
  s.fit = fit;
  ctx.document.apply(s, label);
}

}  // namespace hermite::app
