#pragma once
// The elapsed time of a long step on stderr, only when stderr is a terminal (never in pipes,
// files or tests): after the first second, "fit: 3.2 s" redrawn in place four times a second;
// the line is cleared when the step ends, so the command's own output follows as usual.

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace hermite::app {

class TerminalProgress {
 public:
  // `label` names the step ("fitting 5210 samples").
  explicit TerminalProgress(std::string label);
  ~TerminalProgress();
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

 private:
  void run();

  std::string label_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool drawn_ = false;
  std::thread thread_;
};

}  // namespace hermite::app
