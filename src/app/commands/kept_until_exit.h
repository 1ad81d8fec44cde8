#pragma once
// Objects a command is done with just before the process ends (`mesh`'s fit): kept alive until
// exit instead of destroyed, so the operating system reclaims their memory with the process at
// once. Destroying a partition-of-unity fit of 200 000 samples frees its 73 000 local models
// one by one on one core: 0.14 s of the elephant's 4-second `mesh` (docs/performance.md,
// "Serial stretches of mesh"). The objects stay reachable (from a static list), so leak checkers
// do not report them; a process that keeps many (a test runner) holds their memory until it ends.

#include <memory>

namespace hermite::app {

// Keeps `object` alive until the process ends (thread-safe).
void keepUntilExit(std::shared_ptr<const void> object);

}  // namespace hermite::app
