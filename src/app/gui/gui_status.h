#pragma once
// The status line: what the program did last, for the status bar and tests.

#include <string>

namespace hermite::app {

struct GuiStatus {
  std::string message;
  bool error = false;

  void set(std::string text, bool isError = false) {
    message = std::move(text);
    error = isError;
  }
};

}  // namespace hermite::app
