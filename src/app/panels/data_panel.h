#pragma once
// The Data section: the preset and its sample count, the teaching scenes, open / save, export of
// the samples, the zero set and the model, normals re-estimated or flipped, and a summary of the
// samples with the data warnings.

#include <string>

#include "app/gui/gui_context.h"
#include "app/panels/zero_set_export.h"

namespace hermite::app {

class DataPanel {
 public:
  explicit DataPanel(GuiContext& ctx);
  void draw();
  // An "Export mesh" runs (zero_set_export.h), or has finished and its result waits for a frame.
  bool exporting() const { return zeroSetExport_.running(); }
  bool exportFinished() const { return zeroSetExport_.hasResult(); }

 private:
  void drawSource();
  void drawFiles();
  void drawNormals();
  void drawSummary();

  GuiContext& ctx_;
  void drawZeroSetExport();

  std::string openPath_, exportPath_, zeroSetPath_ = "zero-set.glb";
  ZeroSetExport zeroSetExport_;
};

}  // namespace hermite::app
