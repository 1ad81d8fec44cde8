#include "app/gui/document_actions.h"

#include "app/gui/camera_framing.h"
#include "io/mesh_file.h"
#include "io/point_file.h"
#include "scene/scene_fit.h"

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

// A point file: the fit and view settings stay, the data is replaced.
void openPointFile(GuiContext& ctx, const std::string& path) {
  try {
    const int dim = pointFileDimension(path);
    Scene s = ctx.scene();
    s.mode = dim == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d;
    s.data = DataSpec{};
    s.data.file = path;
    s.data.resolvedFile = path;
    std::vector<std::string> warnings;
    // Read now, so a malformed file is reported here and not as a failed fit.
    if (dim == 2) sceneSamples<2>(s, warnings);
    else sceneSamples<3>(s, warnings);
    s.view.bounds.reset();
    ctx.document.apply(s, "open " + path);
    ctx.selected = -1;
    ctx.setStatus("loaded " + path);
  } catch (const std::exception& e) {
    ctx.setStatus(e.what(), true);
  }
}

}  // namespace

void openFile(GuiContext& ctx, const std::string& path) {
  if (path.size() > 5 && path.substr(path.size() - 5) == ".json")
    openScene(ctx, path);
  else if (ctx.scene().mode == SceneMode::HoleFill)
    openHoleFillMesh(ctx, path);
  else
    openPointFile(ctx, path);
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
