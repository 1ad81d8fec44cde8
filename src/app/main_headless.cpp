// hermite-lab-cli: fit, eval, mesh, holefill and patch-table without the display's libraries, so
// that a scripted command loads a dozen fewer shared libraries (docs/performance.md, Process
// start-up). The launcher, hermite-lab, runs it for those commands (src/launcher/launcher.c).
#include "app/commands/cli.h"

int main(int argc, char** argv) { return hermite::app::runProgram(argc, argv, hermite::app::DisplayCommands{}); }
