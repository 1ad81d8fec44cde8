#include "app/panels/data_panel.h"

#include <imgui.h>

#include <filesystem>
#include <type_traits>

#include "app/commands/commands.h"
#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "core/base/errors.h"
#include "core/points/normal_estimation.h"
#include "core/shapes/presets.h"
#include "io/atomic_file.h"
#include "io/point_file.h"
#include "scene/scene_fit.h"

#ifndef HERMITE_SCENES_DIR
#define HERMITE_SCENES_DIR "assets/scenes"
#endif

namespace hermite::app {

namespace {

std::vector<std::filesystem::path> teachingScenes() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(HERMITE_SCENES_DIR, ec))
    if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

DataPanel::DataPanel(GuiContext& ctx)
    : ctx_(ctx), openPath_(ctx.document.path()), exportPath_(ctx.dimension() == 2 ? "samples.xyn" : "samples.xyzn") {}

void DataPanel::draw() {
  drawSource();
  drawFiles();
  drawNormals();
  ImGui::Separator();
  drawSummary();
}

// The preset (and its sample count) or a teaching scene.
void DataPanel::drawSource() {
  const Scene& s = ctx_.scene();
  const std::string current = !s.data.preset.empty() ? s.data.preset : !s.data.file.empty() ? s.data.file : "inline samples";
  if (ImGui::BeginCombo("preset", current.c_str())) {
    for (const PresetInfo& p : allPresets()) {
      const std::string label = p.name + (p.dimension == 2 ? "  (2D)" : "  (3D)");
      if (ImGui::Selectable(label.c_str(), p.name == s.data.preset))
        loadPreset(ctx_, p.name, p.dimension == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
    }
    ImGui::EndCombo();
  }
  if (ImGui::BeginCombo("teaching scene", "open...")) {
    for (const auto& path : teachingScenes())
      if (ImGui::Selectable(path.stem().string().c_str())) openScene(ctx_, path.string());
    ImGui::EndCombo();
  }
  if (!s.data.preset.empty()) {
    int count = s.data.count;
    const PresetInfo& info = presetInfo(s.data.preset);
    ImGui::SetNextItemWidth(120);
    if (ImGui::InputInt("count (0 = own)", &count, 10, 100, ImGuiInputTextFlags_EnterReturnsTrue)) {
      count = count == 0 ? 0 : std::clamp(count, info.minCount, info.maxCount);
      Scene n = s;
      n.data.count = count;
      ctx_.document.apply(n, "sample count");
    }
  }
}

// Open, save, and export of the samples, the zero set and the model.
void DataPanel::drawFiles() {
  inputText("##open", openPath_);
  ImGui::SameLine();
  if (ImGui::Button("Open")) {
    openFile(ctx_, openPath_);
  }
  helpMarker("A scene (.json), a point file (.xyz .pwn .xyzn .xyn) or a mesh file (.ply .obj .gltf .glb .off): a data "
             "file opens as a default scene around it. Files can also be dropped onto the window.");
  inputText("##save", ctx_.savePath);
  ImGui::SameLine();
  if (ImGui::Button("Save scene")) saveScene(ctx_, ctx_.savePath);
  inputText("##export", exportPath_);
  ImGui::SameLine();
  if (ImGui::Button("Export samples")) {
    try {
      const FitOutcome* fit = ctx_.currentFit();
      if (!fit) throw InputError("no samples to export yet");
      if (!fit->visitImplicit([&](const auto& f) { savePointFile(exportPath_, f.data); }))
        throw InputError("no samples to export in this mode");
      ctx_.setStatus("exported samples to " + exportPath_);
    } catch (const std::exception& e) {
      ctx_.setStatus(e.what(), true);
    }
  }
  drawZeroSetExport();
  if (ImGui::Button("Export model (JSON)")) {
    try {
      if (!ctx_.currentFit()) throw InputError("no fitted model yet");
      const std::string path = std::filesystem::path(ctx_.savePath).replace_extension(".model.json").string();
      writeFileAtomically(path, fittedModelJson(*ctx_.currentFit()) + "\n");
      ctx_.setStatus("exported the model to " + path);
    } catch (const std::exception& e) {
      ctx_.setStatus(e.what(), true);
    }
  }
}

// Every normal re-estimated (PCA + spanning-tree orientation) or flipped.
// "Export mesh" runs on its own thread (zero_set_export.h); the button cancels it meanwhile and
// the summary line or the error goes to the status bar when it ends.
void DataPanel::drawZeroSetExport() {
  if (const std::optional<ZeroSetExport::Result> r = zeroSetExport_.take()) ctx_.setStatus(r->message, !r->ok);
  inputText("##zeroset", zeroSetPath_);
  ImGui::SameLine();
  if (zeroSetExport_.running()) {
    if (ImGui::Button("Cancel export")) zeroSetExport_.cancel();
  } else if (ImGui::Button("Export mesh")) {
    if (!ctx_.currentFit()) ctx_.setStatus("no fitted model yet", true);
    else if (zeroSetExport_.start(ctx_.fits.shown(), zeroSetPath_)) ctx_.setStatus("exporting " + zeroSetPath_ + " …");
  }
  helpMarker("The zero set over view.bounds as `hermite-lab mesh` makes it with its defaults: marching cubes (3D: "
             ".glb .gltf .ply .obj) or squares (2D: .obj .svg) at the automatic resolution, with chord refinement; "
             "the window keeps drawing meanwhile.");
}

void DataPanel::drawNormals() {
  const int dim = ctx_.dimension();
  if (ImGui::Button("Re-estimate normals")) {
    try {
      std::vector<std::string> warnings;
      Scene n = dim == 2 ? withInlineSamples<2>(ctx_.scene(), warnings) : withInlineSamples<3>(ctx_.scene(), warnings);
      if (dim == 2) {
        HermiteSamples<2> d = inlineSamples<2>(n);
        d.normals = estimateNormals<2>(d.points);
        setInlineSamples<2>(n, d);
      } else {
        HermiteSamples<3> d = inlineSamples<3>(n);
        d.normals = estimateNormals<3>(d.points);
        setInlineSamples<3>(n, d);
      }
      ctx_.document.apply(n, "re-estimate normals");
      ctx_.setStatus("normals re-estimated (PCA over 10 neighbours, oriented along a spanning tree)");
    } catch (const std::exception& e) {
      ctx_.setStatus(e.what(), true);
    }
  }
  helpMarker("Replace every normal by the PCA estimate over its nearest neighbours, oriented consistently "
             "(minimum spanning tree) and outward.");
  ImGui::SameLine();
  const bool flipAll = ImGui::Button("Flip all normals");
  ctx_.recordWidget("data.flip_all");
  if (flipAll) {
    std::vector<std::string> warnings;
    Scene n = dim == 2 ? withInlineSamples<2>(ctx_.scene(), warnings) : withInlineSamples<3>(ctx_.scene(), warnings);
    for (auto& normal : n.data.normals)
      for (double& c : normal) c = -c;
    ctx_.document.apply(n, "flip all normals");
  }
}

// How many samples, their spacing, the selection and the data warnings.
void DataPanel::drawSummary() {
  // Always three lines, so nothing below (the Fit panel's r slider) moves while one drags it;
  // the warnings themselves are listed in Diagnostics.
  const int dim = ctx_.dimension();
  // A fit of other data (the file just opened is still fitting) describes nothing shown here.
  const FitOutcome* f = ctx_.currentFit();
  if (f && !(f->scene.data == ctx_.scene().data)) f = nullptr;
  const auto& loaded = ctx_.loadedData;
  const bool fresh = !f && loaded && loaded->data == ctx_.scene().data;
  int n = fresh ? loaded->samples : 0;
  double spacing = fresh ? loaded->spacing : 0;
  if (f) f->visitImplicit([&](const auto& fit) {
    n = fit.samples.size();
    spacing = f->sampleSpacing();
  });
  if (n > 0) ImGui::Text("%d samples (%dD), mean spacing %.4g%s", n, dim, spacing, fresh ? ", fitting..." : "");
  else ImGui::TextDisabled("samples: fitting...");
  if (ctx_.selected >= 0) ImGui::Text("selected: sample %d (N flips, Del deletes)", ctx_.selected);
  else ImGui::TextDisabled("no sample selected");
  const std::size_t warnings = f ? f->warnings().size() : fresh ? loaded->warnings.size() : 0;
  if (warnings > 0) {
    ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %zu data / fit warnings (Diagnostics)", warnings);
    if (ImGui::IsItemHovered()) {  // the warnings in full
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
      for (const std::string& w : f ? f->warnings() : loaded->warnings) ImGui::TextUnformatted(("! " + w).c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  } else {
    ImGui::TextDisabled("no warnings");
  }
}


}  // namespace hermite::app
