#pragma once
// Writing command output. A failed write (closed pipe, full disk) is an EnvironmentError
// (exit 4), never a silent truncation.

#include <string_view>

namespace hermite::app {

void writeStdout(std::string_view text);
// Flushes stdout; EnvironmentError when anything written could not be delivered.
void finishStdout();

}  // namespace hermite::app
