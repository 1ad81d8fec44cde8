#include "app/cli.h"

namespace hermite::app {

int runCli(int, char**) { return 0; }

}  // namespace hermite::app
