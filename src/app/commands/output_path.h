#pragma once
// Checks on an output path made before any work is done: its extension (UsageError, exit 2) and
// whether it can be written at all (EnvironmentError, exit 4).

#include <string>
#include <vector>

namespace hermite::app {

// The lower-case extension of `path` without the dot ("" when none).
std::string lowerExtension(const std::string& path);

// UsageError naming `command`, the path and the accepted extensions unless the extension is one
// of `accepted` (lower case, without the dot).
std::string requireExtension(const std::string& command, const std::string& path,
                             const std::vector<std::string>& accepted);

// EnvironmentError when `path` names a directory or its directory does not exist.
void requireWritableLocation(const std::string& command, const std::string& path);

}  // namespace hermite::app
