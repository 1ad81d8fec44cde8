// hermite-lab-main: the full program (every command, the window). The launcher, hermite-lab, runs
// it for everything but the headless commands (src/launcher/launcher.c).
#include "app/commands/cli.h"

int main(int argc, char** argv) {
  return hermite::app::runProgram(argc, argv, hermite::app::allDisplayCommands());
}
