#pragma once
// The Data section's "Export mesh": the zero set of the fit on screen meshed and saved as
// `hermite-lab mesh` does with its defaults (exportZeroSet: the automatic resolution, chord
// refinement on), on a thread of its own at the view worker's lowered priority, so that the window
// keeps drawing. One export at a time; cancel() (or destruction) stops it within a batch of field
// evaluations.

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/base/cancel_token.h"

namespace hermite::app {

struct FitOutcome;

class ZeroSetExport {
 public:
  struct Result {
    std::string message;  // the summary line, or the error
    bool ok = false;
  };

  ZeroSetExport() = default;
  ~ZeroSetExport();
  ZeroSetExport(const ZeroSetExport&) = delete;
  ZeroSetExport& operator=(const ZeroSetExport&) = delete;

  // Starts meshing `fit` into `path`; false (nothing started) while an export runs.
  bool start(std::shared_ptr<const FitOutcome> fit, const std::string& path);
  bool running() const { return running_.load(); }
  void cancel() { cancel_.cancel(); }
  // The finished export's result, once; none while it runs or when none finished since.
  std::optional<Result> take();
  bool hasResult() const;

 private:
  void join();

  std::thread thread_;
  std::atomic<bool> running_{false};
  CancelToken cancel_;
  mutable std::mutex mutex_;
  std::optional<Result> result_;
};

}  // namespace hermite::app
