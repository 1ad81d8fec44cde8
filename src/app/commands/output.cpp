#include "app/commands/output.h"

#include <cstdio>

#include "core/base/errors.h"
#include "scene/scene_fit.h"

namespace hermite::app {

void writeStdout(std::string_view text) {
  if (text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size())
    throw EnvironmentError("cannot write to standard output");
}

void finishStdout() {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) throw EnvironmentError("cannot write to standard output");
}

void printDataWarnings(const SceneFitReport& fit) {
  for (int i = 0; i < fit.dataWarnings && i < static_cast<int>(fit.warnings.size()); ++i)
    std::fprintf(stderr, "warning: %s\n", fit.warnings[static_cast<std::size_t>(i)].c_str());
}

}  // namespace hermite::app
