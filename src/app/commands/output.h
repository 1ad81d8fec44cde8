#pragma once
// Writing command output. A failed write (closed pipe, full disk) is an EnvironmentError
// (exit 4), never a silent truncation.

#include <string_view>

namespace hermite {
struct SceneFitReport;
}

namespace hermite::app {

void writeStdout(std::string_view text);
// The warnings about the data file (estimated or re-oriented normals, merged duplicates) on
// standard error, one `warning:` line each: what `mesh`, `eval`, `render` and `sweep` say of
// their input (`fit` lists every warning itself).
void printDataWarnings(const SceneFitReport& fit);
// Flushes stdout; EnvironmentError when anything written could not be delivered.
void finishStdout();

}  // namespace hermite::app
