#pragma once
// The subcommands of hermite-lab (docs/cli.md). Each returns the process exit code and
// throws hermite errors (errors.h) that runCli maps to exit codes.

#include <array>
#include <string>
#include <vector>

#include "core/base/cancel_token.h"

namespace hermite::app {

struct SceneArgs {
  std::string scenePath;                // empty: the built-in demo scene
  std::vector<std::string> overrides;   // --set KEY=VALUE, in order
};

struct FitArgs {
  SceneArgs scene;
  bool json = false;
  bool coefficients = false;
  bool verify = false;  // --verify: as transform.verify = true
};
int runFit(const FitArgs& args);

struct EvalArgs {
  SceneArgs scene;
  std::string probeFile;  // --at FILE
};
int runEval(const EvalArgs& args);

struct BenchArgs {
  bool json = false;
  std::string only;  // substring of the benchmark names to run; empty = all
  bool quick = false;  // fewer repetitions (used by tests)
};
int runBench(const BenchArgs& args);

struct PatchTableArgs {
  int samples = 15;     // N × N local parameters per patch
  std::string splits;   // "1x1,2x1,2x2,3x3" (empty: that default)
  std::string domain;   // "U0,U1,V0,V1" (empty: 0,1,0,1)
  bool json = false;
};
int runPatchTable(const PatchTableArgs& args);

struct RenderArgs {
  SceneArgs scene;
  std::string output;              // -o OUT.png (required)
  std::string size;                // --size WxH; empty: the scene's view.size
  bool ui = false;                 // --ui: the application's panels on top
  bool explore = false;            // --explore (with --ui): the r explorer open, its sweep run to the end
  std::string backend = "osmesa";  // --backend osmesa | egl
  double uiScale = 1.0;            // --ui-scale S: the panels' scale with --ui
};
int runRender(const RenderArgs& args);

struct SweepArgs {
  SceneArgs scene;
  std::string radii;               // --radii A:B:K
  std::string outputDirectory;     // -o DIR (created when missing)
  std::string size;                // --size WxH; empty: the scene's view.size
  std::string backend = "osmesa";
  bool overwrite = false;          // --overwrite: reuse a folder holding an earlier sweep
  std::string sheet;               // --sheet FILE.png: also a contact sheet of every image; empty: none
};
int runSweep(const SweepArgs& args);

// "WxH" → {W, H}, each in [1, 16384]; UsageError otherwise (render, sweep).
std::array<int, 2> parseImageSize(const std::string& text);
// `mesh --resolution` when not given (docs/cli.md): in 3D round(0.6·√N) cells along the longest
// side for N samples, clamped to [64, 256] — the surface crosses about res² cells, so this keeps
// the samples per crossed cell near those of 200 000 scanned points at 256³ (screened Poisson's
// depth 8), where the mesh closes and beats Poisson's distances; at 64³ those points mesh open
// (cells coarser than the data reach, docs/maths.md "No data"). 2D: 64.
int autoMeshResolution(int dimension, long long samples);
inline constexpr int kAutoMeshResolutionMax = 256;
// `mesh --chord-tolerance` when not given, in grid cells (docs/cli.md).
inline constexpr double kDefaultChordTolerance = 0.02;
struct MeshArgs {
  SceneArgs scene;
  std::string output;   // -o OUT.{glb,gltf,ply,obj} (3D) or OUT.{obj,svg} (2D), required
  int resolution = 0;  // --resolution N: cells along the longest side of view.bounds; 0: autoMeshResolution
  // --chord-tolerance F: split edges whose chord strays > F cells (0: off). 0.02 by default: at
  // 256³ on 200 000 scanned points it halves the mesh's mean and p99 distance to the surface
  // (below screened Poisson's) for about a tenth of the command's time (docs/performance.md).
  double chordTolerance = kDefaultChordTolerance;
};
int runMesh(const MeshArgs& args);
// Meshes a fitted implicit's zero set over view.bounds (marching cubes / squares) into `output`
// (.glb .gltf .ply .obj; 2D .obj .svg); returns the one-line summary `mesh` prints. Also the GUI's
// Export button. chordTolerance > 0 (3D): chord refinement (chord_refinement.h), in grid cells.
// `cancel` (null: none) stops it between batches of evaluations (throws Cancelled).
struct FitOutcome;
std::string exportZeroSet(const FitOutcome& fit, const std::string& output, int resolution, double chordTolerance = 0,
                          const CancelToken* cancel = nullptr);

struct HoleFillArgs {
  std::string input;                   // a triangle mesh (mesh_io.h formats)
  std::string output;                  // -o OUT.{glb,gltf,ply,obj}, required
  bool json = false;
  int rings = 2;                       // --rings: vertex rings around each hole given to the fit
  std::string implicit = "rbf-offset"; // --implicit rbf-offset | hrbf
  bool allowOpen = false;              // --allow-open: holes left open still exit 0
};
int runHoleFill(const HoleFillArgs& args);

// The program's main job without a subcommand (gui/gui_window.cpp): the GUI window on the scene
// (or the demo scene); without a display, the fit report of the scene and a note saying why.
// uiScale > 0: --ui-scale; 0: the monitor's content scale.
int runDefault(const SceneArgs& args, double uiScale = 0);

}  // namespace hermite::app
