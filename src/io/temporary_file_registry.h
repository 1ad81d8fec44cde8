#pragma once
// Temporary files that a SIGINT or SIGTERM removes before the process ends.
//
// A registration installs handlers for SIGINT and SIGTERM where the signal has its default
// action (a handler or an "ignore" installed by somebody else is kept). The
// handler unlinks every registered path — unlink is async-signal-safe — then restores the
// default action and raises the signal again, so the exit status still says "killed by signal".
// Paths live in fixed slots (no allocation in the handler); a path longer than the slot, or a
// registration beyond the slot count, is simply not removed on a signal.

#include <string>

namespace hermite {

void registerTemporaryFile(const std::string& path);
void unregisterTemporaryFile(const std::string& path);

}  // namespace hermite
