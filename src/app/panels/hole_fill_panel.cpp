// The hole-filling mode: the pipeline shown stage by stage — holes (red
// boundaries), the advancing-front patch, the faired patch, the implicit's ring samples (green
// normals), the projection — with the mesh source, the implicit kind, the rings, the figures of
// the run, and export of the filled mesh.

#include <imgui.h>

#include "app/panels/hole_fill_panel.h"

#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "io/mesh_file.h"

namespace hermite::app {

namespace {

const ImVec4 kNoteColour(1.0f, 0.75f, 0.2f, 1.0f);  // repair and hole notes

// The mesh to fill: a preset (a mesh file is opened by the panel's Open button).
bool drawMeshPresets(HoleFillSpec& h, std::string& label) {
  bool changed = false;
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
  return changed;
}

// The stage shown, the implicit's kind and its rings.
bool drawStageOptions(GuiContext& ctx, HoleFillSpec& h, std::string& label) {
  bool changed = false;
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
  ctx.recordWidget("holefill.stage");
  const HoleImplicitKind kinds[] = {HoleImplicitKind::RbfOffset, HoleImplicitKind::Hrbf};
  changed |= comboOf("implicit", h.implicit, kinds, [](HoleImplicitKind k) {
    return std::string_view(k == HoleImplicitKind::Hrbf ? "hrbf" : "rbf-offset (x^3 + linear)");
  });
  int rings = h.rings;
  if (ImGui::SliderInt("rings", &rings, 1, 6)) {
    h.rings = rings;
    changed = true;
  }
  return changed;
}

// The run's figures: mesh size, holes filled, the projection's residual, repair notes, and a
// line per hole (open ones in red, their reason as a tooltip).
void drawHoleSummary(const HoleFillStages& st, bool projected, bool showTimings) {
  int filled = 0;
  for (const auto& hole : st.holes) filled += hole.filled;
  ImGui::Text("%d vertices, %d triangles", st.input.vertexCount(), st.input.triangleCount());
  ImGui::Text("holes %d, filled %d, triangles added %d", int(st.holes.size()), filled, st.trianglesAdded);
  if (projected) ImGui::Text("max |f| %.2g, unconverged %d", st.maxAbsF, st.unconverged);
  if (showTimings) ImGui::Text("%.1f ms", st.ms);
  for (const std::string& note : st.repairMessages) ImGui::TextColored(kNoteColour, "! %s", note.c_str());
  for (std::size_t k = 0; k < st.holes.size(); ++k) {
    const HoleFillStageHole& hole = st.holes[k];
    const std::string method = hole.method.empty() ? "-" : hole.method;
    if (hole.filled)
      ImGui::Text("hole %d: %d edges, %s, filled", int(k), int(hole.loop.size()), method.c_str());
    else
      ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "hole %d: %d edges, %s, open", int(k),
                         int(hole.loop.size()), method.c_str());
    if (!hole.filled && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", hole.reason.c_str());
  }
  for (const auto& hole : st.holes)
    for (const std::string& note : hole.notes) ImGui::TextColored(kNoteColour, "! %s", note.c_str());
}

}  // namespace

void HoleFillPanel::drawLabels() const {
  const FitOutcome* f = ctx_.fits.shown().get();
  const HoleFillStages* stages = f ? f->as<HoleFillStages>() : nullptr;
  if (ctx_.scene().mode != SceneMode::HoleFill || !stages) return;
  const HoleFillStages& st = *stages;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const Camera cam = sceneCamera(ctx_.scene(), ctx_.view.w, ctx_.view.h);
  const Vec<2> o = ctx_.view.origin();
  for (std::size_t k = 0; k < st.holes.size(); ++k) {
    const BoundaryLoop& loop = st.holes[k].loop;
    if (loop.empty()) continue;
    Vec<3> centre = Vec<3>::Zero();
    for (int v : loop) centre += st.input.vertices.col(v);
    centre /= double(loop.size());
    const std::optional<Vec<2>> shown = cam.projectVisible(centre);
    if (!shown) continue;
    const Vec<2> q = *shown + o;
    const std::string text = std::to_string(k);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    const ImVec2 at(float(q.x()) - 0.5f * size.x, float(q.y()) - 0.5f * size.y);
    dl->AddRectFilled(ImVec2(at.x - 3, at.y - 1), ImVec2(at.x + size.x + 3, at.y + size.y + 1),
                      st.holes[k].filled ? IM_COL32(20, 90, 90, 210) : IM_COL32(160, 30, 20, 220), 3.0f);
    dl->AddText(at, IM_COL32(255, 255, 255, 255), text.c_str());
  }
}

void HoleFillPanel::draw() {
  Scene s = ctx_.scene();
  std::string label = "hole filling";
  bool changed = drawMeshPresets(s.holefill, label);
  inputText("##meshfile", meshPath_);
  ImGui::SameLine();
  if (ImGui::Button("Open mesh")) {
    openHoleFillMesh(ctx_, meshPath_);
    return;
  }
  helpMarker("OFF, OBJ, PLY (ascii or binary), glTF / GLB. The holes are its boundary loops.");
  changed |= drawStageOptions(ctx_, s.holefill, label);
  if (changed) ctx_.document.apply(s, label);

  const FitOutcome* f = ctx_.fits.shown().get();
  const HoleFillStages* shownStages = f ? f->as<HoleFillStages>() : nullptr;
  if (!shownStages) return;
  ImGui::Separator();
  drawHoleSummary(*shownStages, ctx_.scene().holefill.stage == HoleFillStage::Project, ctx_.options.showTimings);
  inputText("##export", meshExportPath_);
  ImGui::SameLine();
  if (ImGui::Button("Export mesh")) {
    try {
      saveMesh(meshExportPath_, shownStages->result);
      ctx_.setStatus("wrote " + meshExportPath_);
    } catch (const std::exception& e) {
      ctx_.setStatus(e.what(), true);
    }
  }
}

}  // namespace hermite::app
