// The full program's display commands, apart from cli.cpp so that the headless program, which
// links cli.cpp, pulls in none of them (nor OpenGL, GLFW or X11 through them).
#include "app/commands/cli.h"

namespace hermite::app {

DisplayCommands allDisplayCommands() { return {runRender, runSweep, runBench, runDefault}; }

}  // namespace hermite::app
