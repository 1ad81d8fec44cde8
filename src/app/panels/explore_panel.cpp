#include "app/panels/explore_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>

#include "app/gui/colour_range.h"
#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "app/gui/log_axis.h"
#include "io/atomic_file.h"
#include "render/ui_font.h"

namespace hermite::app {

namespace {

constexpr ImU32 kCurrentColour = IM_COL32(70, 150, 255, 255);    // the scene's r
constexpr ImU32 kSuggestedColour = IM_COL32(255, 160, 40, 255);  // the suggested r
constexpr ImU32 kRejectedColour = IM_COL32(230, 70, 60, 255);    // ill-conditioned / failed rows
constexpr ImU32 kSeriesColour = IM_COL32(235, 235, 235, 255);    // the curve and candidate points
constexpr ImU32 kAxisTextColour = IM_COL32(190, 190, 190, 255);
constexpr ImU32 kGridColour = IM_COL32(70, 70, 80, 255);
// Thumbnails at UI scale 1 (4:3, as the view); scaled with the UI and shrunk to the strip's height.
constexpr float kThumbW = 128.0f, kThumbH = 96.0f;

// Line widths and dot radii in pixels at UI scale 1, times this: the type's size over its size at
// scale 1, so strokes grow with the UI scale as the text does.
float strokeScale() { return ImGui::GetFontSize() / render::kUiFontPixels; }

// One plot's geometry: the whole frame (p0, size) and the data area [a, b] inside it, in pixels.
struct PlotFrame {
  ImVec2 p0, size, a, b;
};

// log10 range of the plotted values, whole decades (y axis).
struct DecadeRange {
  double lo = 0, hi = 1;
};

// Horizontal grid lines and labels at whole decades, thinned so labels stay a line apart.
void drawYAxis(ImDrawList* dl, const PlotFrame& f, const DecadeRange& y) {
  const float fh = ImGui::GetFontSize();
  const int decades = int(y.hi - y.lo);
  const int fit = std::max(1, int((f.b.y - f.a.y) / (fh + 2)));
  const int step = std::max(1, (decades + fit - 1) / fit);
  char buf[32];
  for (int k = int(y.lo); k <= int(y.hi); k += step) {
    const float py = float(f.b.y - (k - y.lo) / (y.hi - y.lo) * (f.b.y - f.a.y));
    if (k != int(y.lo) && k != int(y.hi)) dl->AddLine(ImVec2(f.a.x, py), ImVec2(f.b.x, py), kGridColour);
    std::snprintf(buf, sizeof buf, "1e%d", k);
    const float w = ImGui::CalcTextSize(buf).x;
    dl->AddText(ImVec2(f.a.x - w - 4, py - fh / 2), kAxisTextColour, buf);
  }
}

// Vertical grid lines and labels at the log axis' ticks; "r" names the axis in the lower-left corner.
// A label that would overlap the previous one is left out (its grid line stays).
void drawXAxis(ImDrawList* dl, const PlotFrame& f, const LogAxis& x) {
  const float gap = ImGui::CalcTextSize(" ").x;
  float previousEnd = -FLT_MAX;  // right edge of the last label drawn
  for (const AxisTick& t : x.ticks()) {
    dl->AddLine(ImVec2(float(t.pixel), f.a.y), ImVec2(float(t.pixel), f.b.y), kGridColour);
    const float w = ImGui::CalcTextSize(t.label.c_str()).x, left = float(t.pixel) - w / 2;
    if (left < previousEnd + gap) continue;
    dl->AddText(ImVec2(left, f.b.y + 2), kAxisTextColour, t.label.c_str());
    previousEnd = left + w;
  }
  dl->AddText(ImVec2(f.p0.x + 4, f.b.y + 2), IM_COL32(230, 230, 230, 255), "r:");
}

// A vertical line at r with its label ("suggested 0.154") on text line `line` below the top,
// right of the line, or left of it where it would leave the plot.
void drawMarker(ImDrawList* dl, const PlotFrame& f, const LogAxis& x, double r, ImU32 colour, const char* name, int line) {
  const float px = float(x.toPixel(r)), fh = ImGui::GetFontSize();
  dl->AddLine(ImVec2(px, f.a.y), ImVec2(px, f.b.y), colour, 2.0f * strokeScale());
  char label[64];
  std::snprintf(label, sizeof label, "%s %.3g", name, r);
  const float w = ImGui::CalcTextSize(label).x;
  const float tx = px + 3 + w <= f.b.x ? px + 3 : std::max(f.a.x, px - 3 - w);  // never over the y labels
  dl->AddText(ImVec2(tx, f.a.y + 1 + line * fh), colour, label);
}

// The curve through the rows' finite, positive values: candidates as dots, rejected rows as rings.
template <class Value>
void drawSeries(ImDrawList* dl, const std::vector<RadiusSweepRow>& rows, Value value, const LogAxis& x,
                const std::function<float(double)>& toY) {
  ImVec2 prev;
  bool havePrev = false;
  for (const RadiusSweepRow& r : rows) {
    const double v = value(r);
    if (!(std::isfinite(v) && v > 0)) {
      havePrev = false;
      continue;
    }
    const ImVec2 q(float(x.toPixel(r.radius)), toY(v));
    const float s = strokeScale();
    if (havePrev) dl->AddLine(prev, q, kSeriesColour, 1.5f * s);
    if (!r.rejection().empty()) dl->AddCircle(q, 3.5f * s, kRejectedColour, 0, 1.5f * s);
    else dl->AddCircleFilled(q, 3.0f * s, kSeriesColour);
    prev = q;
    havePrev = true;
  }
}

// One diagnostic against r, log-log: `title` over the plot, decades of the value on y (rows where
// it is not finite or ≤ 0 are left out of the line), r on x; markers for the current and the
// suggested r. Returns the radius clicked (snapped to the nearest swept radius within 8 px), or 0.
template <class Value>
double drawPlot(const char* title, const char* meaning, const std::vector<RadiusSweepRow>& rows, Value value,
                double current, int best, ImVec2 size) {
  ImGui::PushID(title);
  PlotFrame f;
  f.p0 = ImGui::GetCursorScreenPos();
  f.size = size;
  ImGui::InvisibleButton("plot", size);
  const bool hovered = ImGui::IsItemHovered(), clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float fh = ImGui::GetFontSize(), pad = 6;
  f.a = ImVec2(f.p0.x + 3.0f * fh, f.p0.y + fh + pad);
  f.b = ImVec2(f.p0.x + size.x - pad, f.p0.y + size.y - fh - 4);
  dl->AddRectFilled(f.p0, ImVec2(f.p0.x + size.x, f.p0.y + size.y), IM_COL32(25, 27, 32, 255), 3.0f);
  dl->AddRect(f.a, f.b, IM_COL32(110, 110, 120, 255));
  dl->AddText(ImVec2(f.p0.x + 4, f.p0.y + 2), IM_COL32(230, 230, 230, 255), title);

  double rLo = current > 0 ? current : DBL_MAX, rHi = current > 0 ? current : 0;
  DecadeRange y{DBL_MAX, -DBL_MAX};
  for (const RadiusSweepRow& r : rows) {
    rLo = std::min(rLo, r.radius);
    rHi = std::max(rHi, r.radius);
    const double v = value(r);
    if (std::isfinite(v) && v > 0) {
      y.lo = std::min(y.lo, std::floor(std::log10(v)));
      y.hi = std::max(y.hi, std::ceil(std::log10(v)));
    }
  }
  if (!(y.hi >= y.lo)) y = DecadeRange{};
  if (y.hi == y.lo) y.hi = y.lo + 1;
  // Points stay a dot's radius inside the data area.
  const LogAxis x(rLo, rHi, f.a.x + pad, f.b.x - pad);
  const std::function<float(double)> toY = [&](double v) {
    return float(f.b.y - pad - (std::log10(v) - y.lo) / (y.hi - y.lo) * (f.b.y - f.a.y - 2 * pad));
  };
  drawYAxis(dl, f, y);
  drawXAxis(dl, f, x);
  if (best >= 0) drawMarker(dl, f, x, rows[std::size_t(best)].radius, kSuggestedColour, "suggested", 0);
  if (current > 0) drawMarker(dl, f, x, current, kCurrentColour, "current", 1);
  drawSeries(dl, rows, value, x, toY);
  double picked = 0;
  if (hovered || clicked) {
    const double mx = ImGui::GetIO().MousePos.x;
    picked = x.fromPixel(mx);
    for (const RadiusSweepRow& r : rows)
      if (std::abs(x.toPixel(r.radius) - mx) <= 8) picked = r.radius;
    if (hovered) ImGui::SetTooltip("%s\nr = %.4g: click to set r", meaning, picked);
  }
  ImGui::PopID();
  return clicked ? picked : 0;
}

// What the markers and points mean, in one line of their own colours.
void drawPlotLegend() {
  const auto swatch = [](ImU32 colour, const char* text, bool ring) {
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float fh = ImGui::GetFontSize();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 c(p.x + fh / 2, p.y + fh / 2 + 1);
    if (ring) dl->AddCircle(c, fh * 0.3f, colour, 0, 1.5f * strokeScale());
    else if (colour == kSeriesColour) dl->AddCircleFilled(c, fh * 0.25f, colour);
    else dl->AddLine(ImVec2(c.x, p.y + 1), ImVec2(c.x, p.y + fh), colour, 2.0f * strokeScale());
    ImGui::Dummy(ImVec2(fh, fh));
    ImGui::SameLine(0, 4);
    ImGui::TextUnformatted(text);
    ImGui::SameLine(0, fh);
  };
  swatch(kCurrentColour, "current r", false);
  swatch(kSuggestedColour, "suggested r", false);
  swatch(kSeriesColour, "a swept radius", false);
  swatch(kRejectedColour, "rejected (ill-conditioned or failed)", true);
  ImGui::TextDisabled("both axes logarithmic; click a plot to set r");
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
  // The legend, then the plots on the left and the thumbnail strip (scrolling) to their right.
  if (!rows.empty()) {
    drawPlotLegend();
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
  ImGui::SetNextItemWidth(ctx_.px(90));
  ImGui::InputInt("##count", &explorer_.count, 1, 2);
  explorer_.count = std::clamp(explorer_.count, 1, 24);
  ImGui::SameLine();
  ImGui::TextUnformatted("from");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ctx_.px(90));
  ImGui::InputDouble("##from", &explorer_.lower, 0, 0, "%.4g");
  ImGui::SameLine();
  ImGui::TextUnformatted("to");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ctx_.px(90));
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
    ImGui::ProgressBar(explorer_.progress(), ImVec2(ctx_.px(120), 0));
    ImGui::SameLine();
    if (ImGui::Button("Stop")) explorer_.cancel();
  }
}

void ExplorePanel::drawCsvExport(const std::vector<RadiusSweepRow>& rows) {
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ctx_.px(140));
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
      const SceneViewResult t = thumbnailRenderer_.render(entries[k].fit, look, int(ctx_.px(kThumbW)),
                                                          int(ctx_.px(kThumbH)), ViewQuality::Settled);
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
  // Two text lines and the scroll bar under each thumbnail; the image shrinks to what is left.
  const ImGuiStyle& style = ImGui::GetStyle();
  const float below = 2 * ImGui::GetTextLineHeightWithSpacing() + style.ScrollbarSize + 2 * style.FramePadding.y;
  const float thumbH = std::clamp(ImGui::GetContentRegionAvail().y - below, ctx_.px(24), ctx_.px(kThumbH));
  const ImVec2 thumb(thumbH * kThumbW / kThumbH, thumbH);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    ImGui::BeginGroup();
    const RadiusSweepRow& row = entries[k].row;
    if (k < thumbnails_.size() && thumbnails_[k].valid()) {
      ImGui::PushID(int(k));
      if (ImGui::ImageButton(reinterpret_cast<ImTextureID>(std::uintptr_t(thumbnails_[k].id())), thumb))
        adoptRadius(ctx_, row.radius);
      ImGui::PopID();
    } else {
      ImGui::Dummy(ImVec2(thumb.x + 2 * style.FramePadding.x, thumb.y + 2 * style.FramePadding.y));
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

// Condition, residual and validation error against r, side by side, as tall as the strip leaves
// (the UI scale included); a click sets r.
void ExplorePanel::drawPlots(const std::vector<RadiusSweepRow>& rows, int best) const {
  const double current = ctx_.scene().fit.radius;
  const float w = std::clamp((ImGui::GetContentRegionAvail().x - 2 * ctx_.px(kThumbW) - ctx_.px(40)) / 3,
                             ctx_.px(150.0f), ctx_.px(300.0f));
  const float h = std::max(ctx_.px(60.0f), ImGui::GetContentRegionAvail().y);
  double picked = drawPlot("condition estimate", "condition estimate of the fit's system (above 1e14: rejected)", rows,
                           [](const RadiusSweepRow& r) { return r.ok() ? r.conditionEstimate : NAN; }, current, best,
                           ImVec2(w, h));
  ImGui::SameLine();
  const double p2 = drawPlot("residual at the samples", "max |f(p)| + max |grad f(p) - n| over the samples", rows,
                             [](const RadiusSweepRow& r) { return r.ok() ? r.maxAbsF + r.maxGradError : NAN; }, current,
                             best, ImVec2(w, h));
  ImGui::SameLine();
  const double p3 = drawPlot("validation error", "leave-one-out (global fits) or 5-fold error: what the suggestion ranks by",
                             rows, [](const RadiusSweepRow& r) { return r.validationError; }, current, best,
                             ImVec2(w, h));
  if (p2 > 0) picked = p2;
  if (p3 > 0) picked = p3;
  if (picked > 0) adoptRadius(ctx_, picked);
}

}  // namespace hermite::app
