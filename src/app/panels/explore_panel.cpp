#include "app/panels/explore_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "io/atomic_file.h"

namespace hermite::app {

// The range starts around the scene's radius: a tenth of it to three times it.
ExplorePanel::ExplorePanel(GuiContext& ctx) : ctx_(ctx) {
  const double r = ctx.scene().fit.radius;
  if (r > 0) {
    explorer_.lower = r / 10;
    explorer_.upper = r * 3;
  }
}

void ExplorePanel::draw() {
  const ImGuiIO& io = ImGui::GetIO();
  const float h = kExplorerHeight;
  ImGui::SetNextWindowPos(ImVec2(kLeftPanelWidth, io.DisplaySize.y - kStatusBarHeight - h), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::max(100.0f, io.DisplaySize.x - kLeftPanelWidth), h), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.92f);
  if (!ImGui::Begin("Explore r", &ctx_.panels.explore,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings |
                        ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_HorizontalScrollbar)) {
    ImGui::End();
    return;
  }
  drawControls();
  const std::vector<ExplorerEntry> entries = explorer_.entries();
  std::vector<RadiusSweepRow> rows;
  for (const auto& e : entries) rows.push_back(e.row);
  drawCsvExport(rows);
  updateThumbnails(entries);
  const int best = suggestedRadiusIndex(rows);
  drawEntries(entries, best);
  if (!rows.empty()) drawPlots(rows, best);
  ImGui::End();
}

// k, the radius range, Run / Restart and Stop with the progress.
void ExplorePanel::drawControls() {
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
  const bool radius = Kernel{ctx_.scene().fit.kernel, 1.0}.usesRadius();
  ImGui::BeginDisabled(!radius);
  if (ImGui::Button(explorer_.running() ? "Restart" : "Run")) {
    try {
      explorer_.start(ctx_.scene(), logSpacedRadii(explorer_.lower, explorer_.upper, explorer_.count));
      ctx_.setStatus("exploring r");
    } catch (const std::exception& e) {
      ctx_.setStatus(e.what(), true);
    }
  }
  ImGui::EndDisabled();
  if (!radius) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s has no radius", toString(kernelName(ctx_.scene().fit.kernel)).c_str());
  }
  if (explorer_.running()) {
    ImGui::SameLine();
    ImGui::ProgressBar(explorer_.progress(), ImVec2(120, 0));
    ImGui::SameLine();
    if (ImGui::Button("Stop")) explorer_.cancel();
  }
}

void ExplorePanel::drawCsvExport(const std::vector<RadiusSweepRow>& rows) {
  ImGui::SameLine();
  ImGui::SetNextItemWidth(140);
  inputText("##csv", csvPath_);
  ImGui::SameLine();
  if (ImGui::Button("Export CSV")) {
    try {
      writeFileAtomically(csvPath_, radiusSweepCsv(rows));
      ctx_.setStatus("wrote " + csvPath_);
    } catch (const std::exception& e) {
      ctx_.setStatus(e.what(), true);
    }
  }
}

// Thumbnails (drawn on this thread: GL) when new entries arrived.
void ExplorePanel::updateThumbnails(const std::vector<ExplorerEntry>& entries) {
  if (thumbnailGeneration_ == explorer_.generation()) return;
  thumbnailGeneration_ = explorer_.generation();
  thumbnails_.resize(entries.size());
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (!entries[k].fit || thumbnails_[k].valid()) continue;
    try {
      const SceneViewResult t = thumbnailRenderer_.render(entries[k].fit, ctx_.scene(), 128, 96, ViewQuality::Settled);
      thumbnails_[k] = render::Texture::create2D(GL_RGBA8, t.image.width, t.image.height);
      thumbnails_[k].setFilter(GL_LINEAR, GL_LINEAR);
      thumbnails_[k].upload2D(GL_RGBA, GL_UNSIGNED_BYTE, t.image.pixels.data());
    } catch (const std::exception&) {
      // The entry shows its error text instead.
    }
  }
}

// One thumbnail per radius (a click adopts it), its r (* = suggested) and condition.
void ExplorePanel::drawEntries(const std::vector<ExplorerEntry>& entries, int best) {
  for (std::size_t k = 0; k < entries.size(); ++k) {
    ImGui::BeginGroup();
    const RadiusSweepRow& row = entries[k].row;
    if (k < thumbnails_.size() && thumbnails_[k].valid()) {
      ImGui::PushID(int(k));
      if (ImGui::ImageButton(reinterpret_cast<ImTextureID>(std::uintptr_t(thumbnails_[k].id())), ImVec2(128, 96))) {
        FitSpec f = ctx_.scene().fit;
        f.radius = row.radius;
        editFit(ctx_, f, "radius from explorer");
        ctx_.setStatus("adopted r = " + std::to_string(row.radius));
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
}

// Plots of the diagnostics against r (log10 of each, in radius order), minimum marked.
void ExplorePanel::drawPlots(const std::vector<RadiusSweepRow>& rows, int best) const {
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

}  // namespace hermite::app
