#pragma once
// How a failed command reports: the message on standard error with its class's prefix and, when
// the command line asked for --json, also one JSON object on standard output (docs/cli.md,
// "Errors as JSON"), so scripts that read stdout get JSON either way.

#include <string>

namespace hermite::app {

// Remembers whether argv holds --json (before any parsing, so usage errors report as JSON too).
void noteJsonRequested(int argc, char** argv);

// Writes "PREFIX: MESSAGE" to stderr and, with --json, {"error", "exit_code", "file", "line",
// "key"} to stdout (file / line / key read from the message's "FILE:LINE:" or "FILE: KEY:"
// prefix, null when it has none). Returns exitCode.
int reportError(int exitCode, const std::string& prefix, const std::string& message);

// The parts of a message's prefix: "scene.json:12:5: …", "scene.json: fit.radius: …".
struct ErrorPlace {
  std::string file, key;
  int line = 0;  // 0: none
};
ErrorPlace errorPlace(const std::string& message);

}  // namespace hermite::app
