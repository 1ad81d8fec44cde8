#pragma once
// The hermite-lab command line (DESIGN.md §5). Returns the process exit code.

namespace hermite::app {

int runCli(int argc, char** argv);

}  // namespace hermite::app
