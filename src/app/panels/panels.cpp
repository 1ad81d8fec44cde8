// The panels of the window, in a fixed layout (ImGui 1.86 has no docking): the
// left column holds Data, Fit, Compare and View as collapsing sections; Diagnostics sits at the
// top right; Explore r is a strip along the bottom; a status bar below everything. Panels edit
// the Document (each change one undo step; sliders one step per drag) and never call the solver.

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands/commands.h"
#include "app/gui/gui_app.h"
#include "app/gui/gui_widgets.h"
#include "core/base/errors.h"
#include "core/points/hermite_samples.h"
#include "core/points/normal_estimation.h"
#include "core/shapes/presets.h"
#include "io/atomic_file.h"
#include "io/point_file.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"

#ifndef HERMITE_SCENES_DIR
#define HERMITE_SCENES_DIR "assets/scenes"
#endif

namespace hermite::app {

namespace {


const Polynomial kPolys[] = {Polynomial::None, Polynomial::Linear, Polynomial::Quadratic};

std::vector<std::filesystem::path> teachingScenes() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(HERMITE_SCENES_DIR, ec))
    if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

template <int Dim>
int sampleCount(const FitOutcome* f) {
  if constexpr (Dim == 2) return f && f->fit2 ? f->fit2->samples.size() : 0;
  else return f && f->fit3 ? f->fit3->samples.size() : 0;
}

}  // namespace

// ---- documents --------------------------------------------------------------------------------

void GuiApp::openScene(const std::string& path) {
  try {
    Scene s = loadSceneFile(path);
    document_.reset(s, path);
    homeCamera_ = s.view.camera;
    homeCenter_ = s.view.center2d;
    homeHalfHeight_ = s.view.halfHeight2d;
    selected_ = -1;
    savePath_ = path;
    setStatus("opened " + path);
  } catch (const std::exception& e) {
    setStatus(e.what(), true);
  }
}

void GuiApp::loadPreset(const std::string& preset, SceneMode mode) {
  Scene s = scene();
  s.mode = mode;
  s.data = DataSpec{};
  s.data.preset = preset;
  s.view.bounds.reset();
  document_.apply(s, "preset " + preset);
  selected_ = -1;
  setStatus("preset " + preset);
}

void GuiApp::saveScene(const std::string& path) {
  try {
    document_.save(path);
    setStatus("saved " + path);
  } catch (const std::exception& e) {
    setStatus(e.what(), true);
  }
}

void GuiApp::editFit(const FitSpec& fit, const std::string& label) {
  if (fit == scene().fit) return;
  Scene s = scene();
  s.fit = fit;
  document_.apply(s, label);
}

// ---- panels -----------------------------------------------------------------------------------

void GuiApp::recordWidget(const std::string& key) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  widgets_[key] = {a.x, a.y, b.x, b.y};
}

std::optional<std::array<float, 4>> GuiApp::widgetRect(const std::string& key) const {
  const auto it = widgets_.find(key);
  if (it == widgets_.end()) return std::nullopt;
  return it->second;
}

void GuiApp::drawPanels() {
  widgets_.clear();
  const ImGuiIO& io = ImGui::GetIO();
  const float bottom = io.DisplaySize.y - kStatusBarHeight;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::min(kLeftPanelWidth, io.DisplaySize.x), std::max(50.0f, bottom)), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.90f);
  if (ImGui::Begin("Hermite Lab", nullptr,
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                       ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing)) {
    ImGui::PushItemWidth(-110.0f);
    if (scene().mode == SceneMode::Patch || scene().mode == SceneMode::HoleFill) {
      ImGui::SetNextItemOpen(true, ImGuiCond_Once);
      if (scene().mode == SceneMode::Patch) {
        if (ImGui::CollapsingHeader("Patch")) drawPatchPanel();
      } else if (ImGui::CollapsingHeader("Hole filling")) {
        drawHoleFillPanel();
      }
      inputText("##save", savePath_);
      ImGui::SameLine();
      if (ImGui::Button("Save scene")) saveScene(savePath_);
    } else {
      ImGui::SetNextItemOpen(panels.data, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Data")) drawDataPanel();
      ImGui::SetNextItemOpen(panels.fit, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Fit")) drawFitPanel();
      ImGui::SetNextItemOpen(panels.compare, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Compare")) drawComparePanel();
      ImGui::SetNextItemOpen(panels.transform, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Transform")) drawTransformPanel();
    }
    ImGui::SetNextItemOpen(panels.view, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("View")) drawViewPanel();
    if (scene().mode == SceneMode::Implicit2d || scene().mode == SceneMode::Implicit3d) {
      ImGui::Checkbox("Explore r", &panels.explore);
      ImGui::SameLine();
    }
    ImGui::Checkbox("Help (F1)", &panels.help);
    ImGui::PopItemWidth();
  }
  ImGui::End();
  if (panels.diagnostics) drawDiagnosticsPanel();
  if (panels.explore && (scene().mode == SceneMode::Implicit2d || scene().mode == SceneMode::Implicit3d))
    drawExplorePanel();
}

void GuiApp::drawDataPanel() {
  const Scene& s = scene();
  const int dim = s.dimension();
  const std::string current = !s.data.preset.empty() ? s.data.preset : !s.data.file.empty() ? s.data.file : "inline samples";
  if (ImGui::BeginCombo("preset", current.c_str())) {
    for (const PresetInfo& p : allPresets()) {
      const std::string label = p.name + (p.dimension == 2 ? "  (2D)" : "  (3D)");
      if (ImGui::Selectable(label.c_str(), p.name == s.data.preset))
        loadPreset(p.name, p.dimension == 2 ? SceneMode::Implicit2d : SceneMode::Implicit3d);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
    }
    ImGui::EndCombo();
  }
  if (ImGui::BeginCombo("teaching scene", "open...")) {
    for (const auto& path : teachingScenes())
      if (ImGui::Selectable(path.stem().string().c_str())) openScene(path.string());
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
      document_.apply(n, "sample count");
    }
  }
  inputText("##open", openPath_);
  ImGui::SameLine();
  if (ImGui::Button("Open")) {
    FrameInput drop;
    drop.droppedFiles = {openPath_};
    handleDroppedFiles(drop);
  }
  helpMarker("A scene (.json) or a point file (.xyz .pwn .xyzn .xyn ...). Files can also be dropped onto the window.");
  inputText("##save", savePath_);
  ImGui::SameLine();
  if (ImGui::Button("Save scene")) saveScene(savePath_);
  inputText("##export", exportPath_);
  ImGui::SameLine();
  if (ImGui::Button("Export samples")) {
    try {
      const FitOutcome* fit = currentFit();
      if (!fit) throw InputError("no samples to export yet");
      if (dim == 2) savePointFile(exportPath_, fit->fit2->data);
      else savePointFile(exportPath_, fit->fit3->data);
      setStatus("exported samples to " + exportPath_);
    } catch (const std::exception& e) {
      setStatus(e.what(), true);
    }
  }
  inputText("##zeroset", zeroSetPath_);
  ImGui::SameLine();
  if (ImGui::Button("Export mesh")) {
    try {
      if (!currentFit()) throw InputError("no fitted model yet");
      setStatus(exportZeroSet(*currentFit(), zeroSetPath_, 96));
    } catch (const std::exception& e) {
      setStatus(e.what(), true);
    }
  }
  helpMarker("The zero set over view.bounds by marching cubes (3D: .glb .gltf .ply .obj) or squares (2D: .obj .svg).");
  if (ImGui::Button("Export model (JSON)")) {
    try {
      if (!currentFit()) throw InputError("no fitted model yet");
      const std::string path = std::filesystem::path(savePath_).replace_extension(".model.json").string();
      writeFileAtomically(path, fittedModelJson(*currentFit()) + "\n");
      setStatus("exported the model to " + path);
    } catch (const std::exception& e) {
      setStatus(e.what(), true);
    }
  }
  if (ImGui::Button("Re-estimate normals")) {
    try {
      std::vector<std::string> warnings;
      Scene n = dim == 2 ? withInlineSamples<2>(scene(), warnings) : withInlineSamples<3>(scene(), warnings);
      if (dim == 2) {
        HermiteSamples<2> d = inlineSamples<2>(n);
        d.normals = estimateNormals<2>(d.points);
        setInlineSamples<2>(n, d);
      } else {
        HermiteSamples<3> d = inlineSamples<3>(n);
        d.normals = estimateNormals<3>(d.points);
        setInlineSamples<3>(n, d);
      }
      document_.apply(n, "re-estimate normals");
      setStatus("normals re-estimated (PCA over 10 neighbours, oriented along a spanning tree)");
    } catch (const std::exception& e) {
      setStatus(e.what(), true);
    }
  }
  helpMarker("Replace every normal by the PCA estimate over its nearest neighbours, oriented consistently "
             "(minimum spanning tree) and outward.");
  ImGui::SameLine();
  const bool flipAll = ImGui::Button("Flip all normals");
  recordWidget("data.flip_all");
  if (flipAll) {
    std::vector<std::string> warnings;
    Scene n = dim == 2 ? withInlineSamples<2>(scene(), warnings) : withInlineSamples<3>(scene(), warnings);
    for (auto& normal : n.data.normals)
      for (double& c : normal) c = -c;
    document_.apply(n, "flip all normals");
  }
  ImGui::Separator();
  const FitOutcome* f = currentFit();
  if (f && f->ok()) {
    const int n = dim == 2 ? sampleCount<2>(f) : sampleCount<3>(f);
    const double spacing = dim == 2 ? meanSampleSpacing<2>(f->fit2->samples.points) : meanSampleSpacing<3>(f->fit3->samples.points);
    ImGui::Text("%d samples (%dD), mean spacing %.4g", n, dim, spacing);
    if (selected_ >= 0) ImGui::Text("selected: sample %d (N flips, Del deletes)", selected_);
    for (const std::string& w : f->warnings())
      ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %s", w.c_str());
  }
}

void GuiApp::drawFitPanel() {
  FitSpec fit = scene().fit;
  const FitMethod methods[] = {FitMethod::Hrbf, FitMethod::RbfOffset};
  if (comboOf("method", fit.method, methods, fitMethodName)) editFit(fit, "method");
  if (comboOf("kernel", fit.kernel, allKernelTypes(), kernelName)) editFit(fit, "kernel");
  recordWidget("fit.kernel");

  // r: logarithmic slider (one undo step per drag) and exact text entry.
  const Kernel kernel{fit.kernel, fit.radius};
  double spacing = 0;
  if (shown_ && shown_->fit2) spacing = meanSampleSpacing<2>(shown_->fit2->samples.points);
  if (shown_ && shown_->fit3) spacing = meanSampleSpacing<3>(shown_->fit3->samples.points);
  ImGui::BeginDisabled(!kernel.usesRadius());
  double r = fit.radius;
  const double rMin = 1e-4, rMax = 100.0;
  if (ImGui::SliderScalar("r", ImGuiDataType_Double, &r, &rMin, &rMax, "%.4g", ImGuiSliderFlags_Logarithmic)) {
    if (!document_.inGesture()) document_.begin("radius");
    Scene s = scene();
    s.fit.radius = std::clamp(r, rMin, rMax);
    document_.update(s);
  }
  recordWidget("fit.radius");
  if (ImGui::IsItemDeactivated() && document_.inGesture()) document_.end();  // one undo step per drag
  double typed = fit.radius;
  if (ImGui::InputDouble("r exact", &typed, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue) && typed > 0 &&
      std::isfinite(typed)) {
    FitSpec f = fit;
    f.radius = typed;
    editFit(f, "radius");
  }
  if (spacing > 0 && kernel.usesRadius()) ImGui::Text("r = %.3g x mean spacing (%.3g)", fit.radius / spacing, spacing);
  ImGui::EndDisabled();
  if (!kernel.usesRadius()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s has no radius (scale-free): r is ignored", toString(kernelName(fit.kernel)).c_str());
    ImGui::PopStyleColor();
  }

  if (comboOf("polynomial", fit.polynomial, kPolys, polynomialName)) editFit(fit, "polynomial");
  double lambda = fit.smoothing;
  if (ImGui::InputDouble("smoothing", &lambda, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) && lambda >= 0) {
    fit.smoothing = lambda;
    editFit(fit, "smoothing");
    fit = scene().fit;
  }
  helpMarker("lambda >= 0: approximation instead of interpolation (0 interpolates).");
  if (fit.method == FitMethod::RbfOffset) {
    double shift = fit.shift;
    if (ImGui::InputDouble("shift", &shift, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && shift > 0) {
      fit.shift = shift;
      editFit(fit, "shift");
      fit = scene().fit;
    }
  }
  ImGui::Separator();
  ImGui::TextDisabled("partition of unity");
  bool pu = fit.partition.enabled;
  if (ImGui::Checkbox("enabled", &pu)) {
    fit.partition.enabled = pu;
    editFit(fit, pu ? "partition on" : "partition off");
    fit = scene().fit;
  }
  ImGui::BeginDisabled(!fit.partition.enabled);
  int maxPoints = fit.partition.maxPointsPerBox;
  if (ImGui::InputInt("max points / box", &maxPoints, 1, 10, ImGuiInputTextFlags_EnterReturnsTrue) && maxPoints >= 1) {
    fit.partition.maxPointsPerBox = maxPoints;
    editFit(fit, "max points per box");
    fit = scene().fit;
  }
  double box = fit.partition.boxSize;
  if (ImGui::InputDouble("box size", &box, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && box >= 0) {
    fit.partition.boxSize = box;
    editFit(fit, "box size");
    fit = scene().fit;
  }
  double overlap = fit.partition.overlap;
  if (ImGui::InputDouble("overlap", &overlap, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) && overlap >= 1) {
    fit.partition.overlap = overlap;
    editFit(fit, "overlap");
  }
  ImGui::EndDisabled();
  if (!lastFitError_.empty()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(ImVec4(1, 0.4f, 0.35f, 1), "last fit failed: %s", lastFitError_.c_str());
    ImGui::PopTextWrapPos();
  }
}

void GuiApp::drawComparePanel() {
  ImGui::Checkbox("split view", &compare.enabled);
  helpMarker("The right half shows the same data fitted another way, with the same camera.");
  const char* withNames[] = {"RBF with offset points", "HRBF", "another kernel", "another radius"};
  int with = int(compare.with);
  if (ImGui::Combo("right half", &with, withNames, 4)) compare.with = CompareWith(with);
  if (compare.with == CompareWith::OtherKernel) comboOf("kernel##compare", compare.kernel, allKernelTypes(), kernelName);
  if (compare.with == CompareWith::OtherRadius) {
    double r = compare.radius;
    if (ImGui::InputDouble("r##compare", &r, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && r > 0) compare.radius = r;
  }
  if (compare.enabled && shownCompare_ && (shownCompare_->fit2 || shownCompare_->fit3)) {
    const auto& w = shownCompare_->warnings();
    ImGui::Text("right: %s", shownCompare_->fit2 ? shownCompare_->fit2->report.solver.c_str() : shownCompare_->fit3->report.solver.c_str());
    for (const std::string& m : w) ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %s", m.c_str());
  }
}

void GuiApp::drawViewPanel() {
  Scene s = scene();
  ViewSpec& v = s.view;
  bool changed = false;
  std::string label = "view";
  const char* modes[] = {"2D (implicit2d)", "3D (implicit3d)", "patch editor", "hole filling"};
  const int current = s.mode == SceneMode::Implicit2d ? 0 : s.mode == SceneMode::Patch ? 2 : s.mode == SceneMode::HoleFill ? 3 : 1;
  int mode = current;
  if (ImGui::Combo("mode", &mode, modes, 4) && mode != current) {
    if (mode == 3) {
      Scene n = scene();
      n.mode = SceneMode::HoleFill;
      n.view.camera.eye = {1.2, -1.6, 1.4};
      n.view.camera.target = {0, 0, 0};
      n.view.camera.up = {0, 0, 1};
      document_.apply(n, "hole filling");
    } else if (mode == 2) {
      Scene n = scene();
      n.mode = SceneMode::Patch;
      // A view of the default torus piece.
      n.view.camera.eye = {5.0, 3.5, 3.5};
      n.view.camera.target = {2.2, 1.3, 0.4};
      n.view.camera.up = {0, 0, 1};
      document_.apply(n, "patch editor");
    } else {
      loadPreset(mode == 0 ? "curve2d" : "sphere6", mode == 0 ? SceneMode::Implicit2d : SceneMode::Implicit3d);
    }
    return;
  }
  if (s.mode == SceneMode::Implicit3d) {
    const Projection projections[] = {Projection::Perspective, Projection::Orthographic};
    changed |= comboOf("projection", v.projection, projections, projectionName);
    const TraceMode traces[] = {TraceMode::Auto, TraceMode::Baked, TraceMode::Exact};
    changed |= comboOf("trace", v.trace, traces, traceModeName);
    helpMarker("baked: f on a 3D grid, hits refined against the true field when the view settles. exact: the "
               "model summed per pixel in the shader (slow without a GPU).");
    changed |= ImGui::Checkbox("slice plane", &v.slice.enabled);
    if (v.slice.enabled) {
      const char* axes[] = {"x", "y", "z"};
      int axis = v.slice.normal[0] != 0 ? 0 : v.slice.normal[1] != 0 ? 1 : 2;
      if (ImGui::Combo("slice normal", &axis, axes, 3)) {
        v.slice.normal = {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
        changed = true;
      }
      double offset = v.slice.offset;
      const double extent = sliceOffsetExtent();  // offsets that cut the bounds
      const double lo = -extent, hi = extent;
      if (ImGui::SliderScalar("slice offset", ImGuiDataType_Double, &offset, &lo, &hi, "%.3f")) {
        if (!document_.inGesture()) document_.begin("slice offset");
        v.slice.offset = offset;
        Scene n = scene();
        n.view.slice.offset = offset;
        document_.update(n);
      }
      if (ImGui::IsItemDeactivated() && document_.inGesture()) document_.end();
      ImGui::SameLine();
      helpMarker("or Alt + drag in the view: the plane follows the mouse along its normal.");
    }
    changed |= ImGui::Checkbox("bounds box", &v.showBounds);
    ImGui::SameLine();
  }
  if (s.mode == SceneMode::Implicit2d || s.mode == SceneMode::Implicit3d) {
    changed |= ImGui::Checkbox("points", &v.showPoints);
    ImGui::SameLine();
    changed |= ImGui::Checkbox("normals", &v.showNormals);
  } else {
    const Projection projections[] = {Projection::Perspective, Projection::Orthographic};
    changed |= comboOf("projection", v.projection, projections, projectionName);
  }
  if (s.mode == SceneMode::Implicit2d || s.mode == SceneMode::Implicit3d) {
    ImGui::Checkbox("partition boxes", &showPartitionBoxes_);
    recordWidget("view.partition_boxes");
    helpMarker("The leaves of a partition-of-unity fit (Fit > partition of unity).");
  }
  if (s.mode == SceneMode::Implicit2d) {
    double range = colourRange_;
    if (ImGui::InputDouble("colour range", &range, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && range >= 0)
      colourRange_ = range;
    helpMarker("The heat map covers [-range, range]; 0 = the largest |f| in the view.");
  }
  float bg[3] = {float(v.background[0]), float(v.background[1]), float(v.background[2])};
  if (ImGui::ColorEdit3("background", bg, ImGuiColorEditFlags_NoInputs)) {
    v.background = {bg[0], bg[1], bg[2]};
    changed = true;
    label = "background";
  }
  if (changed) document_.apply(s, label);

  if (ImGui::Button("Fit to view (F)")) fitToView();
  ImGui::SameLine();
  if (ImGui::Button("Reset (Home)")) resetView();
  if (s.mode != SceneMode::Implicit2d) {
    if (ImGui::Button("Store view")) {
      savedViews_.push_back(scene().view.camera);
      setStatus("stored view " + std::to_string(savedViews_.size()));
    }
    for (std::size_t k = 0; k < savedViews_.size(); ++k) {
      ImGui::SameLine();
      if (ImGui::Button(std::to_string(k + 1).c_str()))
        document_.setCamera(savedViews_[k], scene().view.center2d, scene().view.halfHeight2d);
    }
  }
  ImGui::Checkbox("screenshot with panels", &screenshotWithUi_);
  if (ImGui::Button("Screenshot (F12)")) {
    char file[64];
    std::snprintf(file, sizeof file, "/hermite-lab-%03d.png", ++screenshotCounter_);
    requestScreenshot(options_.screenshotDirectory + file, screenshotWithUi_);
  }
}

void GuiApp::drawDiagnosticsPanel() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.90f);
  if (ImGui::Begin("Diagnostics", nullptr,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                       ImGuiWindowFlags_NoFocusOnAppearing)) {
    const FitOutcome* f = shown_.get();
    if (!f) {
      ImGui::TextDisabled(lastFitError_.empty() ? "fitting..." : "no model");
    } else if (f->holefill) {
      ImGui::Text("stage       %s", std::string(holeFillStageName(scene().holefill.stage)).c_str());
      ImGui::Text("holes       %d", int(f->holefill->holes.size()));
      ImGui::Text("added       %d triangles", f->holefill->trianglesAdded);
    } else if (f->patch) {
      const PatchDisplay& v = *f->patch;
      ImGui::Text("patches     %d x %d", v.grid.patchesU(), v.grid.patchesV());
      ImGui::Text("form        %s", std::string(patchFormName(scene().patch.form)).c_str());
      if (!v.vertexError.empty()) ImGui::Text("max error   %.3g", v.maxError);
      if (options_.showTimings) ImGui::Text("tessellate  %.2f ms, view %.0f ms", v.tessellateMs, view_.ms);
    } else {
      const FitReport& r = f->fit2 ? f->fit2->report : f->fit3->report;
      const FitResiduals res = f->fit2 ? fitResiduals(*f->fit2) : fitResiduals(*f->fit3);
      ImGui::Text("solver      %s", r.solver.c_str());
      ImGui::Text("unknowns    %d (%d samples)", r.nUnknowns, r.nSamples);
      if (options_.showTimings) ImGui::Text("fit         %.2f ms", r.fitMs);
      ImGui::Text("condition   %.3g", r.conditionEstimate);
      // Residuals at rounding-noise level differ in their digits between CPUs: below 1e-10
      // only the bound is shown, so headless screenshots agree across machines.
      const auto residual = [](const char* label, double v) {
        if (v < 1e-10) ImGui::Text("%s < 1e-10", label);
        else ImGui::Text("%s %.2e", label, v);
      };
      residual("max |f(p)| ", res.maxAbsF);
      residual("max |grad-n|", res.maxGradError);
      if (options_.showTimings) {
        if (!view_.traceMode.empty()) ImGui::Text("view        %s, %.0f ms", view_.traceMode.c_str(), view_.ms);
        else ImGui::Text("view        %.0f ms", view_.ms);
      } else if (!view_.traceMode.empty()) {
        ImGui::Text("view        %s", view_.traceMode.c_str());
      }
      if (shownVersion_ != document_.version()) ImGui::TextDisabled("(showing an earlier version)");
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 300.0f);
      for (const std::string& w : f->warnings()) ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %s", w.c_str());
      ImGui::PopTextWrapPos();
    }
    if (worker_.busy()) {
      char text[64];
      std::snprintf(text, sizeof text, "fitting %.1f s", worker_.runningMs() / 1000.0);
      ImGui::ProgressBar(float(worker_.progress()), ImVec2(200, 0), text);
      ImGui::SameLine();
      const bool cancelled = ImGui::Button("Cancel");
      recordWidget("diagnostics.cancel");
      if (cancelled) {
        worker_.cancel();
        submittedVersion_ = document_.version();  // do not resubmit what was cancelled
        setStatus("fit cancelled; showing the previous result");
      }
    }
  }
  ImGui::End();
}

void GuiApp::drawExplorePanel() {
  const ImGuiIO& io = ImGui::GetIO();
  const float h = kExplorerHeight;
  ImGui::SetNextWindowPos(ImVec2(kLeftPanelWidth, io.DisplaySize.y - kStatusBarHeight - h), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::max(100.0f, io.DisplaySize.x - kLeftPanelWidth), h), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.92f);
  if (!ImGui::Begin("Explore r", &panels.explore,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings |
                        ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_HorizontalScrollbar)) {
    ImGui::End();
    return;
  }
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("k", &explorer_.count, 1, 2);
  explorer_.count = std::clamp(explorer_.count, 1, 24);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputDouble("from", &explorer_.lower, 0, 0, "%.4g");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputDouble("to", &explorer_.upper, 0, 0, "%.4g");
  ImGui::SameLine();
  const bool radius = Kernel{scene().fit.kernel, 1.0}.usesRadius();
  ImGui::BeginDisabled(!radius);
  if (ImGui::Button(explorer_.running() ? "Restart" : "Run")) {
    try {
      explorer_.start(scene(), logSpacedRadii(explorer_.lower, explorer_.upper, explorer_.count));
      setStatus("exploring r");
    } catch (const std::exception& e) {
      setStatus(e.what(), true);
    }
  }
  ImGui::EndDisabled();
  if (!radius) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s has no radius", toString(kernelName(scene().fit.kernel)).c_str());
  }
  if (explorer_.running()) {
    ImGui::SameLine();
    ImGui::ProgressBar(explorer_.progress(), ImVec2(120, 0));
    ImGui::SameLine();
    if (ImGui::Button("Stop")) explorer_.cancel();
  }
  const std::vector<ExplorerEntry> entries = explorer_.entries();
  ImGui::SameLine();
  ImGui::SetNextItemWidth(140);
  inputText("##csv", csvPath_);
  ImGui::SameLine();
  if (ImGui::Button("Export CSV")) {
    try {
      std::vector<RadiusSweepRow> rows;
      for (const auto& e : entries) rows.push_back(e.row);
      writeFileAtomically(csvPath_, radiusSweepCsv(rows));
      setStatus("wrote " + csvPath_);
    } catch (const std::exception& e) {
      setStatus(e.what(), true);
    }
  }

  // Thumbnails (drawn on this thread: GL) when new entries arrived.
  if (thumbnailGeneration_ != explorer_.generation()) {
    thumbnailGeneration_ = explorer_.generation();
    thumbnails_.resize(entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
      if (!entries[k].fit || thumbnails_[k].valid()) continue;
      try {
        const SceneViewResult t = thumbnailRenderer_.render(entries[k].fit, scene(), 128, 96, ViewQuality::Settled);
        thumbnails_[k] = render::Texture::create2D(GL_RGBA8, t.image.width, t.image.height);
        thumbnails_[k].setFilter(GL_LINEAR, GL_LINEAR);
        thumbnails_[k].upload2D(GL_RGBA, GL_UNSIGNED_BYTE, t.image.pixels.data());
      } catch (const std::exception&) {
        // The entry shows its error text instead.
      }
    }
  }
  std::vector<RadiusSweepRow> rows;
  for (const auto& e : entries) rows.push_back(e.row);
  const int best = suggestedRadiusIndex(rows);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    ImGui::BeginGroup();
    const RadiusSweepRow& row = entries[k].row;
    if (k < thumbnails_.size() && thumbnails_[k].valid()) {
      ImGui::PushID(int(k));
      if (ImGui::ImageButton(reinterpret_cast<ImTextureID>(std::uintptr_t(thumbnails_[k].id())), ImVec2(128, 96))) {
        FitSpec f = scene().fit;
        f.radius = row.radius;
        editFit(f, "radius from explorer");
        setStatus("adopted r = " + std::to_string(row.radius));
      }
      ImGui::PopID();
    } else {
      ImGui::Dummy(ImVec2(136, 104));
    }
    ImGui::Text("%sr = %.3g", int(k) == best ? "* " : "", row.radius);
    if (row.ok()) ImGui::Text("cond %.2g", row.conditionEstimate);
    else ImGui::TextColored(ImVec4(1, 0.4f, 0.35f, 1), "failed");
    ImGui::EndGroup();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("r = %.6g (%.3g x spacing)\nsolver %s\ncondition %.3g\nmax |f(p)| %.2e\nleave-one-out %.3g%s%s",
                        row.radius, row.radiusInSpacing, row.solver.c_str(), row.conditionEstimate, row.maxAbsF,
                        row.looCombined, row.error.empty() ? "" : "\n", row.error.c_str());
    ImGui::SameLine();
  }
  // Plots of the diagnostics against r (log10 of each, in radius order), minimum marked.
  if (!rows.empty()) {
    ImGui::BeginGroup();
    std::vector<float> cond, loo, res;
    for (const auto& r : rows) {
      cond.push_back(r.ok() ? float(std::log10(std::max(r.conditionEstimate, 1e-300))) : 0.0f);
      loo.push_back(std::isfinite(r.looCombined) ? float(std::log10(std::max(r.looCombined, 1e-300))) : 0.0f);
      res.push_back(r.ok() ? float(std::log10(std::max(r.maxAbsF + r.maxGradError, 1e-300))) : 0.0f);
    }
    ImGui::PlotLines("log10 condition", cond.data(), int(cond.size()), 0, nullptr, FLT_MAX, FLT_MAX, ImVec2(180, 40));
    char overlay[64] = "";
    if (best >= 0) std::snprintf(overlay, sizeof overlay, "min at r = %.3g", rows[best].radius);
    ImGui::PlotLines("log10 leave-one-out", loo.data(), int(loo.size()), 0, overlay, FLT_MAX, FLT_MAX, ImVec2(180, 40));
    ImGui::PlotLines("log10 residual", res.data(), int(res.size()), 0, nullptr, FLT_MAX, FLT_MAX, ImVec2(180, 40));
    ImGui::EndGroup();
  }
  ImGui::End();
}

void GuiApp::drawHelpOverlay() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.95f);
  if (ImGui::Begin("Controls", &panels.help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    const char* rows[][2] = {
        {"left drag (3D)", "orbit the camera"},
        {"right / middle drag, Shift+left", "pan"},
        {"wheel", "zoom towards the cursor"},
        {"F / Home", "fit to view / reset the camera"},
        {"click a sample", "select it (highlighted)"},
        {"drag a sample", "move it (3D: on the plane facing the camera)"},
        {"drag the normal's tip", "rotate the normal"},
        {"N / Del", "flip the normal / delete the sample"},
        {"Ctrl+click", "add a sample (3D: on the surface or the slice plane)"},
        {"Alt+drag", "move the slice plane along its normal (3D, slice on)"},
        {"Ctrl+Z / Ctrl+Shift+Z", "undo / redo (every edit, fit settings too)"},
        {"Ctrl+S", "save the scene"},
        {"Tab", "hide / show the panels"},
        {"F12", "screenshot (numbered PNG)"},
        {"F1 or ?", "this help"},
    };
    for (const auto& r : rows) {
      ImGui::TextUnformatted(r[0]);
      ImGui::SameLine(250);
      ImGui::TextDisabled("%s", r[1]);
    }
  }
  ImGui::End();
}

void GuiApp::drawStatusBar() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, io.DisplaySize.y - kStatusBarHeight), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x, kStatusBarHeight), ImGuiCond_Always);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  if (ImGui::Begin("##status", nullptr,
                   ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                       ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus)) {
    const std::string file = document_.path().empty() ? "(unsaved scene)" : document_.path();
    ImGui::Text("%s%s", file.c_str(), document_.dirty() ? " *" : "");
    ImGui::SameLine(320);
    if (status_.error) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", status_.message.c_str());
    else ImGui::TextUnformatted(status_.message.c_str());
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

void GuiApp::drawSelectionOverlay() {
  if (selected_ < 0) return;
  ImDrawList* fg = ImGui::GetBackgroundDrawList();
  auto p = sampleScreenPosition(selected_);
  auto tip = normalTipScreenPosition(selected_);
  if (!p) return;
  *p += viewOrigin();
  if (tip) *tip += viewOrigin();
  fg->AddCircle(ImVec2(float(p->x()), float(p->y())), 7.0f, IM_COL32(255, 200, 0, 255), 16, 2.5f);
  if (tip) {
    fg->AddLine(ImVec2(float(p->x()), float(p->y())), ImVec2(float(tip->x()), float(tip->y())), IM_COL32(255, 200, 0, 255), 2.0f);
    fg->AddCircleFilled(ImVec2(float(tip->x()), float(tip->y())), 5.0f, IM_COL32(255, 200, 0, 255));
  }
}

}  // namespace hermite::app
