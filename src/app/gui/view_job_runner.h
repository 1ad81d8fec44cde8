#pragma once
// One worker thread for the view's slow work (volume bakes, exact refinement, CPU tracing of
// undecided pixels), so that no frame waits for it (docs/design.md, Threads). The newest job
// wins: a submission replaces the job waiting and, unless told to let it finish, cancels the
// running one through its CancelToken and drops a finished result nobody took. A job runs off
// the GL thread and returns the step the GL thread applies (uploads, draws): takeFinished()
// hands over the last one once.
// The thread starts with the first submission (renderers that never submit own none).

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

#include "core/base/cancel_token.h"

namespace hermite::app {

class ViewJobRunner {
 public:
  using Apply = std::function<void()>;                 // runs on the GL thread
  using Job = std::function<Apply(const CancelToken&)>;  // runs on the worker; may throw Cancelled

  ViewJobRunner() = default;
  ~ViewJobRunner();
  ViewJobRunner(const ViewJobRunner&) = delete;
  ViewJobRunner& operator=(const ViewJobRunner&) = delete;

  // letRunningFinish: the running job completes and its result is kept (a drag's coarse bakes:
  // cancelling each for the next would never show one).
  void submit(Job job, bool letRunningFinish = false);
  // The GL step of the last finished job (once), or an empty function. A job that threw (other
  // than Cancelled) gives a step that rethrows its error.
  Apply takeFinished();
  // A job runs or waits, or its result waits to be taken.
  bool busy() const;
  // A finished job's GL step waits to be taken.
  bool hasFinished() const;
  // Cancels the running job and drops the waiting one and any untaken result.
  void cancel();
  // Waits until no job runs or waits (tests); false on timeout.
  bool waitIdle(double timeoutSeconds);

 private:
  void loop();

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  Job waiting_;
  Apply finished_;
  std::shared_ptr<CancelToken> runningToken_;  // set while a job runs
  bool running_ = false, stop_ = false;
  std::thread thread_;
};

}  // namespace hermite::app
