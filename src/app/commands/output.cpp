#include "app/commands/output.h"

#include <cstdio>

#include "core/base/errors.h"

namespace hermite::app {

void writeStdout(std::string_view text) {
  if (text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size())
    throw EnvironmentError("cannot write to standard output");
}

void finishStdout() {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) throw EnvironmentError("cannot write to standard output");
}

}  // namespace hermite::app
