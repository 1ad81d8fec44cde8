#pragma once
// The status line and the message log: what the program did last (the status bar shows it) and
// every message since the window opened, with its time and severity (the message log window,
// panels/message_log.h). Fit warnings go to the log only; the status line keeps the last
// info or error.

#include <chrono>
#include <cstddef>
#include <deque>
#include <string>

namespace hermite::app {

enum class Severity { Info, Warning, Error };

struct LogEntry {
  std::chrono::system_clock::time_point time;
  Severity severity = Severity::Info;
  std::string text;  // the full message, never shortened
};

struct GuiStatus {
  std::string message;
  bool error = false;
  std::deque<LogEntry> log;  // oldest first, at most kMaxLog entries
  static constexpr std::size_t kMaxLog = 1000;

  // A new status line (also logged).
  void set(std::string text, bool isError = false) {
    append(isError ? Severity::Error : Severity::Info, text);
    message = std::move(text);
    error = isError;
  }
  // A message for the log alone (fit warnings: they are listed in Diagnostics as well).
  void append(Severity severity, std::string text) {
    log.push_back(LogEntry{std::chrono::system_clock::now(), severity, std::move(text)});
    if (log.size() > kMaxLog) log.pop_front();
  }
};

}  // namespace hermite::app
