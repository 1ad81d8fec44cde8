#include "app/gui/gui_context.h"

#include <imgui.h>

#include <cstdio>
#include <filesystem>

#include "app/gui/ui_scale.h"

namespace hermite::app {

GuiContext::GuiContext(Document doc, GuiOptions opts)
    : document(std::move(doc)), options(std::move(opts)), uiScale(clampUiScale(options.uiScale)) {
  setHomeFromScene();
  panels.presenter = document.scene().view.presenter;
  // A data file opened as a scene (no scene path) saves beside it as FILE.json.
  const std::string& data = document.scene().data.file;
  savePath = !document.path().empty() ? document.path()
             : !data.empty()          ? std::filesystem::path(data).replace_extension(".json").string()
                                      : "scene.json";
}

void GuiContext::setStatus(std::string message, bool error) { status.set(std::move(message), error); }

void GuiContext::recordWidget(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  widgets[name] = {a.x, a.y, b.x, b.y};
}

void GuiContext::setHomeFromScene() {
  const ViewSpec& v = scene().view;
  home = CameraHome{v.camera, v.center2d, v.halfHeight2d};
}

void GuiContext::requestNumberedScreenshot() {
  char name[64];
  std::snprintf(name, sizeof name, "/hermite-lab-%03d.png", ++screenshotCounter);
  screenshot = ScreenshotRequest{options.screenshotDirectory + name, screenshotWithUi};
}

}  // namespace hermite::app
