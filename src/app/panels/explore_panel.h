#pragma once
// The r explorer strip along the bottom: fits at log-spaced radii on a worker (RadiusExplorer),
// a thumbnail per radius (click adopts it), the suggested radius starred, condition /
// leave-one-out / residual plots against r, CSV export.

#include <string>
#include <vector>

#include "app/gui/explorer.h"
#include "app/gui/scene_view.h"
#include "render/gl/gl_objects.h"

#include "app/gui/gui_context.h"

namespace hermite::app {

class ExplorePanel {
 public:
  explicit ExplorePanel(GuiContext& ctx);
  void draw();
  ~ExplorePanel() { explorer_.cancel(); }
  RadiusExplorer& explorer() { return explorer_; }

 private:
  void drawControls();
  void drawCsvExport(const std::vector<RadiusSweepRow>& rows);
  void updateThumbnails(const std::vector<ExplorerEntry>& entries);
  void drawEntries(const std::vector<ExplorerEntry>& entries, int best);
  void drawPlots(const std::vector<RadiusSweepRow>& rows, int best) const;

  GuiContext& ctx_;
  RadiusExplorer explorer_;
  SceneViewRenderer thumbnailRenderer_;
  std::vector<render::Texture> thumbnails_;  // one per explorer entry, in order
  int thumbnailGeneration_ = -1;
  std::string csvPath_ = "diagnostics.csv";
};

}  // namespace hermite::app
