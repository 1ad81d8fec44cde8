#include "app/gui/view_job_runner.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include <omp.h>

#include <algorithm>

#include "core/base/errors.h"
#include "core/base/threading.h"

namespace hermite::app {

ViewJobRunner::~ViewJobRunner() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    waiting_ = nullptr;
    if (runningToken_) runningToken_->cancel();
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();  // a running job stops at its next poll
}

void ViewJobRunner::submit(Job job, bool letRunningFinish) {
  {
    std::lock_guard lock(mutex_);
    if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
    waiting_ = std::move(job);
    if (!letRunningFinish) {
      finished_ = nullptr;
      if (runningToken_) runningToken_->cancel();
    }
  }
  wake_.notify_all();
}

ViewJobRunner::Apply ViewJobRunner::takeFinished() {
  std::lock_guard lock(mutex_);
  Apply out = std::move(finished_);
  finished_ = nullptr;
  return out;
}

bool ViewJobRunner::busy() const {
  std::lock_guard lock(mutex_);
  return running_ || waiting_ || finished_;
}

bool ViewJobRunner::hasFinished() const {
  std::lock_guard lock(mutex_);
  return bool(finished_);
}

void ViewJobRunner::cancel() {
  std::lock_guard lock(mutex_);
  waiting_ = nullptr;
  finished_ = nullptr;
  if (runningToken_) runningToken_->cancel();
}

bool ViewJobRunner::waitIdle(double timeoutSeconds) {
  std::unique_lock lock(mutex_);
  return idle_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds), [&] { return !running_ && !waiting_; });
}

void ViewJobRunner::loop() {
  // The jobs' OpenMP loops leave one core to the GUI thread and the GL rasteriser's threads: on
  // 2 cores a bake on both made idle frames take 100–200 ms (the window's frame log).
  omp_set_num_threads(std::max(1, std::min(threadCount(), availableCores() - 1)));
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || waiting_; });
    if (stop_) return;
    Job job = std::move(waiting_);
    waiting_ = nullptr;
    auto token = std::make_shared<CancelToken>();
    runningToken_ = token;
    running_ = true;
    lock.unlock();
    Apply apply;
    try {
      apply = job(*token);
    } catch (const Cancelled&) {
    } catch (const std::exception& e) {
      // The GL thread reports it where it reports its own drawing errors.
      apply = [message = std::string(e.what())] { throw InputError(message); };
    }
    job = nullptr;  // what it captured (fits, bakes) goes now, off the GL thread
    lock.lock();
    running_ = false;
    runningToken_.reset();
    if (!token->cancelled()) finished_ = std::move(apply);
    idle_.notify_all();
  }
}

}  // namespace hermite::app
