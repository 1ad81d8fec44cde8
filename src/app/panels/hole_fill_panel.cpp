// The hole-filling mode: the pipeline shown stage by stage — holes (red
// boundaries), the advancing-front patch, the faired patch, the implicit's ring samples (green
// normals), the projection — with the mesh source, the implicit kind, the rings, the figures of
// the run, and export of the filled mesh.

#include <imgui.h>

#include "app/gui/gui_app.h"
#include "app/gui/gui_widgets.h"
#include "io/mesh_file.h"

namespace hermite::app {

void GuiApp::drawHoleFillPanel() {
  Scene s = scene();
  HoleFillSpec& h = s.holefill;
  bool changed = false;
  std::string label = "hole filling";
  const std::string source = h.mesh.empty() ? "preset: " + h.preset : h.mesh;
  if (ImGui::BeginCombo("mesh", source.c_str())) {
    for (const auto& [name, description] : holeFillPresets()) {
      if (ImGui::Selectable(name.c_str(), h.mesh.empty() && name == h.preset)) {
        h.preset = name;
        h.mesh.clear();
        h.resolvedMesh.clear();
        changed = true;
        label = "mesh " + name;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", description.c_str());
    }
    ImGui::EndCombo();
  }
  inputText("##meshfile", meshPath_);
  ImGui::SameLine();
  if (ImGui::Button("Open mesh")) {
    h.mesh = meshPath_;
    h.resolvedMesh = meshPath_;
    changed = true;
    label = "open " + meshPath_;
  }
  helpMarker("OFF, OBJ, PLY (ascii or binary), glTF / GLB. The holes are its boundary loops.");
  const char* stages[] = {"1 holes", "2 advancing front", "3 fairing", "4 implicit fit", "5 projection"};
  int stage = int(h.stage);
  ImGui::TextUnformatted("stage");
  for (int k = 0; k < 5; ++k) {
    if (ImGui::RadioButton(stages[k], stage == k) && stage != k) {
      h.stage = HoleFillStage(k);
      changed = true;
      label = std::string("stage ") + stages[k];
    }
  }
  recordWidget("holefill.stage");
  const HoleImplicitKind kinds[] = {HoleImplicitKind::RbfOffset, HoleImplicitKind::Hrbf};
  changed |= comboOf("implicit", h.implicit, kinds,
                     [](HoleImplicitKind k) { return std::string_view(k == HoleImplicitKind::Hrbf ? "hrbf" : "rbf-offset (x^3 + linear)"); });
  int rings = h.rings;
  if (ImGui::SliderInt("rings", &rings, 1, 6)) {
    h.rings = rings;
    changed = true;
  }
  if (changed) document_.apply(s, label);

  const FitOutcome* f = shown_.get();
  if (f && f->holefill) {
    const HoleFillStages& st = *f->holefill;
    ImGui::Separator();
    int filled = 0;
    for (const auto& hole : st.holes) filled += hole.filled;
    ImGui::Text("%d vertices, %d triangles", st.input.vertexCount(), st.input.triangleCount());
    ImGui::Text("holes %d, filled %d, triangles added %d", int(st.holes.size()), filled, st.trianglesAdded);
    if (scene().holefill.stage == HoleFillStage::Project)
      ImGui::Text("max |f| %.2g, unconverged %d", st.maxAbsF, st.unconverged);
    if (options_.showTimings) ImGui::Text("%.1f ms", st.ms);
    for (const auto& hole : st.holes)
      for (const std::string& note : hole.notes) ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "! %s", note.c_str());
    inputText("##export", meshExportPath_);
    ImGui::SameLine();
    if (ImGui::Button("Export mesh")) {
      try {
        saveMesh(meshExportPath_, st.result);
        setStatus("wrote " + meshExportPath_);
      } catch (const std::exception& e) {
        setStatus(e.what(), true);
      }
    }
  }
}

}  // namespace hermite::app
