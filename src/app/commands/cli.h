#pragma once
// The hermite-lab command line (docs/cli.md). Returns the process exit code.

namespace hermite::app {

int runCli(int argc, char** argv);

}  // namespace hermite::app
