#pragma once
// The application's ImGui panels. For now one: the info / diagnostics panel (scene, mode, fit
// settings, solver, condition estimate, residuals, timings, warnings), drawn the same in the
// window and by `render --ui`. The GUI issue adds the editing panels next to it.
// Panels read plain structs and never call the solver (STYLE.md habit 7).

#include <string>
#include <utility>
#include <vector>

#include "core/scene_fit.h"

namespace hermite::app {

// Everything the info panel shows, filled from a scene and its fit.
struct FitDiagnostics {
  std::string sceneName;
  std::string mode;         // implicit2d, implicit3d, ...
  std::string method;       // hrbf, rbf-offset
  std::string kernel;
  double radius = 0;
  bool radiusUsed = true;   // false for cubic / polyharmonic (radius ignored)
  double meanSpacing = 0;   // mean nearest-neighbour distance of the samples (r in its units)
  std::string polynomial;
  double smoothing = 0;
  int nSamples = 0;
  int nUnknowns = 0;
  std::string solver;
  double conditionEstimate = 0;
  double maxAbsF = 0;       // max |f(pᵢ)| over the (transformed) samples
  double maxGradError = 0;  // max ‖∇f(pᵢ) − nᵢ‖
  double fitMs = 0;
  // Wall-clock figures differ run to run: headless renders (same input → same bytes) hide them.
  bool showTimings = true;
  std::string transform;    // empty: none; else "coefficient-update" / "re-solve"
  std::vector<std::string> warnings;
  // Extra "name: value" lines of the view (colour range, trace mode, ...), in order.
  std::vector<std::pair<std::string, std::string>> viewLines;
};

template <int Dim>
FitDiagnostics fitDiagnostics(const Scene& scene, const SceneFit<Dim>& fit);

// Draws every application panel for the current frame (between ImGui::NewFrame and
// ImGui::Render). Layout is fixed relative to the display so headless frames are reproducible.
void drawAppPanels(const FitDiagnostics& diagnostics);

// The info / diagnostics panel alone, at the top-left corner.
void drawInfoPanel(const FitDiagnostics& diagnostics);

}  // namespace hermite::app
