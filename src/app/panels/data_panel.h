#pragma once
// The Data section: the preset and its sample count, the teaching scenes, open / save, export of
// the samples, the zero set and the model, normals re-estimated or flipped, and a summary of the
// samples with the data warnings.

#include <string>

#include "app/gui/gui_context.h"

namespace hermite::app {

class DataPanel {
 public:
  explicit DataPanel(GuiContext& ctx);
  void draw();

 private:
  void drawSource();
  void drawFiles();
  void drawNormals();
  void drawSummary();

  GuiContext& ctx_;
  std::string openPath_, exportPath_, zeroSetPath_ = "zero-set.glb";
};

}  // namespace hermite::app
