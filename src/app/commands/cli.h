#pragma once
// The hermite-lab command line (docs/cli.md). Returns the process exit code.

#include "app/commands/commands.h"

namespace hermite::app {

// The commands that draw or open a window. The full program (hermite-lab-main) passes them all;
// the headless program (hermite-lab-cli, which the launcher runs for fit, eval, mesh, holefill and
// patch-table) passes none, so that it links and loads no OpenGL, GLFW or X11 library.
struct DisplayCommands {
  int (*render)(const RenderArgs&) = nullptr;
  int (*sweep)(const SweepArgs&) = nullptr;
  int (*bench)(const BenchArgs&) = nullptr;
  int (*window)(const SceneArgs&, double uiScale) = nullptr;
};

// All of them: the full program's set.
DisplayCommands allDisplayCommands();

int runCli(int argc, char** argv, const DisplayCommands& display);

// A program's main(): the BLAS environment (a re-execution when the launcher did not set it),
// the heap's thresholds, then runCli.
int runProgram(int argc, char** argv, const DisplayCommands& display);

}  // namespace hermite::app
