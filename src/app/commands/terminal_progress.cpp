#include "app/commands/terminal_progress.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace hermite::app {

TerminalProgress::TerminalProgress(std::string label) : label_(std::move(label)) {
  if (::isatty(STDERR_FILENO)) thread_ = std::thread([this] { run(); });
}

TerminalProgress::~TerminalProgress() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (drawn_) std::fprintf(stderr, "\r\033[K");  // erase the progress line
  std::fflush(stderr);
}

void TerminalProgress::run() {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  // Quiet for the first second: quick steps print nothing.
  if (wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) return;
  while (!stop_) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::fprintf(stderr, "\r\033[K%s: %.1f s", label_.c_str(), seconds);
    std::fflush(stderr);
    drawn_ = true;
    wake_.wait_for(lock, std::chrono::milliseconds(250), [this] { return stop_; });
  }
}

}  // namespace hermite::app
