#pragma once
// Objects a command is done with just before the process ends (`mesh`'s fit): kept alive until
// exit instead of destroyed, so the operating system reclaims their memory with the process at
// once. Destroying a partition-of-unity fit of 200 000 samples frees its 73 000 local models
// one by one on one core: 0.14 s of the elephant's 4-second `mesh` (docs/performance.md,
// "Serial stretches of mesh"). Only the program's own process keeps them (runProgram enables
// it); a caller that runs commands in-process (a test) frees them as usual. Kept objects stay
// reachable (from a static list), so leak checkers do not report them.

#include <memory>

namespace hermite::app {

// From now on keepUntilExit keeps its objects (the program's process; not undone).
void enableKeepUntilExit();

// Keeps `object` alive until the process ends when enabled, else lets it go now (thread-safe).
void keepUntilExit(std::shared_ptr<const void> object);

}  // namespace hermite::app
