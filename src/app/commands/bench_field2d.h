#pragma once
// The 2D redraw bench of `hermite-lab bench`: how long one drag step of the 2D view takes.

#include <string>

#include "core/rbf/kernels.h"
#include "core/rbf/polynomial.h"

namespace hermite {

// The 2D redraw bench: refit a `points`-sample "curve2d" HRBF and redraw its 2D view
// at size × size (evaluation on the grid of `gridScale`, upload, draw, glFinish), in a context of
// its own (`backend`). Times in ms, medians over `repetitions` after one warm-up round.
struct Field2dBenchOptions {
  int points = 200;
  int size = 512;
  int repetitions = 15;
  double gridScale = 0.25;  // interactive redraws: f, ∇f every 4 px, bilinear in between
  Kernel kernel{KernelType::Cubic, 1.0};  // the scene default; well conditioned at 200 points
  Polynomial polynomial = Polynomial::Linear;
  std::string backend = "osmesa";
};
struct Field2dBenchResult {
  double medianMs = 0;    // refit + evaluate + upload + draw + finish
  double fitMs = 0;       // medians of the parts
  double evaluateMs = 0;
  double drawMs = 0;      // upload + draw + glFinish
  Field2dBenchOptions options;
};
Field2dBenchResult benchField2dRefitRedraw(const Field2dBenchOptions& options = {});

}  // namespace hermite
