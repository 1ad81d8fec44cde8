#pragma once
// What the panels, the shortcuts and dropped files do to the whole document: open a scene,
// a point file or (hole-fill mode) the mesh to fill, load a preset, save, change the fit
// settings. Each is one undo step; failures go to the status line, never an exception.

#include <string>

#include "app/gui/gui_context.h"

namespace hermite::app {

// A scene file replaces the document (and Home becomes its camera).
void openScene(GuiContext& ctx, const std::string& path);
// A scene (.json) opens; in hole-fill mode a mesh file is the mesh to fill; any other point or
// mesh file opens as the default scene around it (loadDataFileScene, as `hermite-lab FILE`); an
// unknown extension is an error naming the accepted ones.
void openFile(GuiContext& ctx, const std::string& path);
// Hole-fill mode: `path` is the mesh to fill.
void openHoleFillMesh(GuiContext& ctx, const std::string& path);
void loadPreset(GuiContext& ctx, const std::string& name, SceneMode mode);
void saveScene(GuiContext& ctx, const std::string& path);
// The scene's fit becomes `fit` (nothing when equal), one undo step named `label`.
void editFit(GuiContext& ctx, const FitSpec& fit, const std::string& label);

}  // namespace hermite::app
