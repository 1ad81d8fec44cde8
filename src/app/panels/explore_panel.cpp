#include "app/panels/explore_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "app/gui/colour_range.h"
#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "app/gui/log_axis.h"
#include "io/atomic_file.h"

namespace hermite::app {

namespace {

constexpr ImU32 kCurrentColour = IM_COL32(70, 150, 255, 255);    // the scene's r
constexpr ImU32 kSuggestedColour = IM_COL32(255, 160, 40, 255);  // the suggested r
constexpr ImU32 kRejectedColour = IM_COL32(230, 70, 60, 255);    // ill-conditioned / failed rows
constexpr float kPlotHeight = 140.0f;  // fits the 200 px strip under the controls
constexpr float kThumbW = 128.0f, kThumbH = 96.0f;

// One diagnostic against r: log10 of `value(row)` on y (rows where it is not finite or ≤ 0 are
// left out of the line), log r on x; markers for the current and the suggested r. Returns the
// radius clicked (snapped to the nearest swept radius within 8 px), or 0.
template <class Value>
double drawPlot(const char* title, const std::vector<RadiusSweepRow>& rows, Value value, double current, int best,
                float width) {
  ImGui::PushID(title);
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("plot", ImVec2(width, kPlotHeight));
  const bool hovered = ImGui::IsItemHovered(), clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float fh = ImGui::GetFontSize();
  const ImVec2 a(p0.x + 3.2f * fh, p0.y + fh + 4), b(p0.x + width - 6, p0.y + kPlotHeight - fh - 6);  // the data area
  dl->AddRectFilled(p0, ImVec2(p0.x + width, p0.y + kPlotHeight), IM_COL32(25, 27, 32, 255), 3.0f);
  dl->AddRect(a, b, IM_COL32(110, 110, 120, 255));
  dl->AddText(ImVec2(p0.x + 4, p0.y + 2), IM_COL32(230, 230, 230, 255), title);

  double rLo = DBL_MAX, rHi = 0, yLo = DBL_MAX, yHi = -DBL_MAX;
  for (const RadiusSweepRow& r : rows) {
    rLo = std::min(rLo, r.radius);
    rHi = std::max(rHi, r.radius);
    const double v = value(r);
    if (std::isfinite(v) && v > 0) {
      yLo = std::min(yLo, std::floor(std::log10(v)));
      yHi = std::max(yHi, std::ceil(std::log10(v)));
    }
  }
  if (current > 0) {
    rLo = std::min(rLo, current);
    rHi = std::max(rHi, current);
  }
  const LogAxis x(rLo, rHi, a.x, b.x);
  if (!(yHi >= yLo)) yLo = 0, yHi = 1;
  if (yHi == yLo) yHi = yLo + 1;
  const auto toY = [&](double v) { return float(b.y - (std::log10(v) - yLo) / (yHi - yLo) * (b.y - a.y)); };
  char buf[32];
  std::snprintf(buf, sizeof buf, "1e%d", int(yHi));
  dl->AddText(ImVec2(p0.x + 3, a.y - 2), IM_COL32(190, 190, 190, 255), buf);
  std::snprintf(buf, sizeof buf, "1e%d", int(yLo));
  dl->AddText(ImVec2(p0.x + 3, b.y - fh + 2), IM_COL32(190, 190, 190, 255), buf);
  for (const AxisTick& t : x.ticks()) {
    dl->AddLine(ImVec2(float(t.pixel), a.y), ImVec2(float(t.pixel), b.y), IM_COL32(70, 70, 80, 255));
    dl->AddText(ImVec2(float(t.pixel) - ImGui::CalcTextSize(t.label.c_str()).x / 2, b.y + 2), IM_COL32(190, 190, 190, 255),
                t.label.c_str());
  }
  dl->AddText(ImVec2(b.x - ImGui::CalcTextSize("r").x, b.y + 2), IM_COL32(230, 230, 230, 255), "r");
  const auto marker = [&](double r, ImU32 colour, const char* label) {
    const float px = float(x.toPixel(r));
    dl->AddLine(ImVec2(px, a.y), ImVec2(px, b.y), colour, 2.0f);
    dl->AddText(ImVec2(px + 3, a.y + 1), colour, label);
  };
  if (best >= 0) marker(rows[std::size_t(best)].radius, kSuggestedColour, "suggested");
  if (current > 0) marker(current, kCurrentColour, "current");
  ImVec2 prev;
  bool havePrev = false;
  for (const RadiusSweepRow& r : rows) {
    const double v = value(r);
    if (!(std::isfinite(v) && v > 0)) {
      havePrev = false;
      continue;
    }
    const ImVec2 q(float(x.toPixel(r.radius)), toY(v));
    if (havePrev) dl->AddLine(prev, q, IM_COL32(235, 235, 235, 255), 1.5f);
    const bool rejected = !r.rejection().empty();
    if (rejected) dl->AddCircle(q, 3.5f, kRejectedColour, 0, 1.5f);
    else dl->AddCircleFilled(q, 3.0f, IM_COL32(235, 235, 235, 255));
    prev = q;
    havePrev = true;
  }
  double picked = 0;
  if (hovered || clicked) {
    const double mx = ImGui::GetIO().MousePos.x;
    picked = x.fromPixel(mx);
    for (const RadiusSweepRow& r : rows)
      if (std::abs(x.toPixel(r.radius) - mx) <= 8) picked = r.radius;
    if (hovered) ImGui::SetTooltip("r = %.4g\nclick to set r", picked);
  }
  ImGui::PopID();
  return clicked ? picked : 0;
}

// Sets the scene's r (one undoable edit) and says so in the status bar.
void adoptRadius(GuiContext& ctx, double r) {
  FitSpec f = ctx.scene().fit;
  f.radius = r;
  editFit(ctx, f, "radius from explorer");
  char buf[64];
  std::snprintf(buf, sizeof buf, "r = %.4g from the explorer", r);
  ctx.setStatus(buf);
}

}  // namespace

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
  // The strip between the left panel and the status bar, at the UI scale.
  const float h = ctx_.px(kExplorerHeight), left = ctx_.px(kLeftPanelWidth);
  ImGui::SetNextWindowPos(ImVec2(left, io.DisplaySize.y - ctx_.px(kStatusBarHeight) - h), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::max(100.0f, io.DisplaySize.x - left), h), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.94f);
  if (!ImGui::Begin("r explorer (E)", &ctx_.panels.explore,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings |
                        ImGuiWindowFlags_NoCollapse)) {
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
  // Plots on the left, the thumbnail strip (scrolling) to their right.
  if (!rows.empty()) {
    drawPlots(rows, best);
    ImGui::SameLine();
  }
  drawEntries(entries, best);
  ImGui::End();
}

// "radii: K from A to B [Run]", Stop with the progress.
void ExplorePanel::drawControls() {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("radii:");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputInt("##count", &explorer_.count, 1, 2);
  explorer_.count = std::clamp(explorer_.count, 1, 24);
  ImGui::SameLine();
  ImGui::TextUnformatted("from");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputDouble("##from", &explorer_.lower, 0, 0, "%.4g");
  ImGui::SameLine();
  ImGui::TextUnformatted("to");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputDouble("##to", &explorer_.upper, 0, 0, "%.4g");
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

// Thumbnails (drawn on this thread: GL) when new entries arrived: the curve or surface first —
// no points or normals — and one colour range for all (thumbnailRange), so they compare.
void ExplorePanel::updateThumbnails(const std::vector<ExplorerEntry>& entries) {
  if (thumbnailGeneration_ == explorer_.generation()) return;
  thumbnailGeneration_ = explorer_.generation();
  thumbnails_.resize(entries.size());
  Scene look = ctx_.scene();
  look.view.showPoints = false;
  look.view.showNormals = false;
  thumbnailRenderer_.colourRange = sharedColourRange(look);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (!entries[k].fit || thumbnails_[k].valid()) continue;
    try {
      const SceneViewResult t = thumbnailRenderer_.render(entries[k].fit, look, int(kThumbW), int(kThumbH), ViewQuality::Settled);
      thumbnails_[k] = render::Texture::create2D(GL_RGBA8, t.image.width, t.image.height);
      thumbnails_[k].setFilter(GL_LINEAR, GL_LINEAR);
      thumbnails_[k].upload2D(GL_RGBA, GL_UNSIGNED_BYTE, t.image.pixels.data());
    } catch (const std::exception&) {
      // The entry shows its error text instead.
    }
  }
}

// One thumbnail per radius in a scrolling strip (a click adopts it), its r (suggested starred)
// and verdict.
void ExplorePanel::drawEntries(const std::vector<ExplorerEntry>& entries, int best) {
  ImGui::BeginChild("thumbnails", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    ImGui::BeginGroup();
    const RadiusSweepRow& row = entries[k].row;
    if (k < thumbnails_.size() && thumbnails_[k].valid()) {
      ImGui::PushID(int(k));
      if (ImGui::ImageButton(reinterpret_cast<ImTextureID>(std::uintptr_t(thumbnails_[k].id())), ImVec2(kThumbW, kThumbH)))
        adoptRadius(ctx_, row.radius);
      ImGui::PopID();
    } else {
      ImGui::Dummy(ImVec2(kThumbW + 8, kThumbH + 8));
    }
    if (int(k) == best) ImGui::TextColored(ImVec4(1, 0.63f, 0.16f, 1), "* r = %.3g", row.radius);
    else ImGui::Text("r = %.3g", row.radius);
    if (!row.rejection().empty()) ImGui::TextColored(ImVec4(0.9f, 0.3f, 0.25f, 1), "%s", row.rejection().c_str());
    else ImGui::Text("cond %.2g", row.conditionEstimate);
    ImGui::EndGroup();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("r = %.6g (%.3g x spacing)\nsolver %s\ncondition %.3g\nmax |f(p)| %.2e\n%s", row.radius,
                        row.radiusInSpacing, row.solver.c_str(), row.conditionEstimate, row.maxAbsF,
                        radiusSweepVerdict(row, ctx_.scene().dimension()).c_str());
    ImGui::SameLine();
  }
  ImGui::EndChild();
}

// Condition, residual and validation error against log r, side by side; a click sets r.
void ExplorePanel::drawPlots(const std::vector<RadiusSweepRow>& rows, int best) const {
  const double current = ctx_.scene().fit.radius;
  const float w = std::clamp((ImGui::GetContentRegionAvail().x - 2 * kThumbW - 40) / 3, 150.0f, 300.0f);
  double picked = drawPlot("condition estimate", rows, [](const RadiusSweepRow& r) { return r.ok() ? r.conditionEstimate : NAN; },
                           current, best, w);
  ImGui::SameLine();
  const double p2 = drawPlot("residual max |f(p)| + max |grad f - n|", rows,
                             [](const RadiusSweepRow& r) { return r.ok() ? r.maxAbsF + r.maxGradError : NAN; }, current,
                             best, w);
  ImGui::SameLine();
  const double p3 = drawPlot("validation error (loo / 5-fold)", rows,
                             [](const RadiusSweepRow& r) { return r.validationError; }, current, best, w);
  if (p2 > 0) picked = p2;
  if (p3 > 0) picked = p3;
  if (picked > 0) adoptRadius(ctx_, picked);
}



}  // namespace hermite::app
