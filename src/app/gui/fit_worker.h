#pragma once
// Fits the document's scene on a worker thread (docs/design.md, Threads: long work off the main thread,
// GL calls on it). The main thread submits (scene, version) and polls each frame:
//   - a newer submission supersedes the pending one (only the latest waits);
//   - cancel() and superseding set the running job's CancelToken: implicit fits stop at their
//     next poll (box by box, phase by phase, factorisation tile by tile; core/base/cancel_token.h)
//     and their result is discarded: the UI keeps the last good result;
//   - progress is the elapsed time against an estimate from the previous fit's size and time
//     (dense fits scale as N³), shown as a bar with a Cancel button.
// A compare scene (the right half of the split view) is fitted in the same job.
// Main scenes that differ from the previous one in one sample only (a drag) are refitted
// through a kept factorisation (drag_refit.h).

#include <atomic>
#include <functional>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>

#include "scene/hole_fill_stages.h"
#include "scene/patch_display.h"
#include "scene/scene_fit.h"

namespace hermite::app {

class DragRefit;

// What fitting one scene gives, by its mode: an implicit fit (2D or 3D), the patch display or
// the hole-filling stages; monostate when the fit failed.
using FitResult = std::variant<std::monostate, SceneFit<2>, SceneFit<3>, PatchDisplay, HoleFillStages>;

// A finished fit of one scene: its result or the error that stopped it (with its exit-code
// class, for the status bar).
struct FitOutcome {
  Scene scene;  // as fitted
  FitResult result;
  std::string error;  // non-empty: no result
  bool cancelled = false;  // the fit stopped because its cancel token was set (error "cancelled")
  double wallMs = 0;  // whole fitScene call, incl. the transform re-solve check

  bool ok() const { return error.empty(); }
  // The result when it is a T, else null.
  template <class T>
  const T* as() const { return std::get_if<T>(&result); }
  // The dimension-free part of an implicit fit (reports, warnings, transform), or null.
  const SceneFitReport* implicitFit() const;
  // Calls fn(const SceneFit<Dim>&) for an implicit fit of either dimension; false otherwise.
  template <class Fn>
  bool visitImplicit(Fn&& fn) const {
    if (const auto* f = as<SceneFit<2>>()) return fn(*f), true;
    if (const auto* f = as<SceneFit<3>>()) return fn(*f), true;
    return false;
  }
  // Samples the implicit fit interpolates (SceneFit::data), 0 for other results.
  int dataCount() const;
  const std::vector<std::string>& warnings() const;  // the fit's warnings (empty on error)
  // What panels show of an implicit fit in every frame, computed on first use and kept: the fit
  // worker asks before it hands a fit over (FitWorker::loop), so that the GUI thread does not
  // walk the samples (or evaluate a dense model at each of them: seconds at 5 000 samples) per
  // frame. meanSampleSpacing of the samples (before the transform), 0 for other results; the
  // residuals at the samples (fitResiduals), zero for other results. Not for concurrent first use.
  double sampleSpacing() const;
  const FitResiduals& residuals() const;

  mutable std::optional<double> sampleSpacing_;
  mutable std::optional<FitResiduals> residuals_;
};

// The fitted model as `fit --coefficients` prints it (docs/cli.md).
std::string fittedModelJson(const FitOutcome& fit);

// Fits `scene` (any mode with a fit); exceptions become FitOutcome::error. `progress`
// (optional) is passed to the long jobs that report it (hole filling: runHoleFillStages);
// `cancel` (optional) to the implicit fits, which stop within ~50 ms of work once it is set
// (FitOutcome::cancelled).
std::shared_ptr<const FitOutcome> fitOutcome(const Scene& scene, const std::function<bool(double)>& progress = {},
                                             const CancelToken* cancel = nullptr);
// The same, throwing the fit's errors (InputError, NumericalError, Cancelled) for the command line.
std::shared_ptr<const FitOutcome> fitOutcomeOrThrow(const Scene& scene,
                                                    const std::function<bool(double)>& progress = {},
                                                    const CancelToken* cancel = nullptr);

struct FitJobResult {
  std::uint64_t version = 0;
  std::shared_ptr<const FitOutcome> main;
  std::shared_ptr<const FitOutcome> compare;  // null when no compare scene was submitted
};

class FitWorker {
 public:
  FitWorker();
  ~FitWorker();
  FitWorker(const FitWorker&) = delete;
  FitWorker& operator=(const FitWorker&) = delete;

  // Queues a fit of `scene` (and `compare`, if given) for document version `version`.
  void submit(const Scene& scene, std::uint64_t version, std::optional<Scene> compare = std::nullopt);
  // Announces a drag of `sample` of the inline `scene` (drag_refit.h): when no fit is waiting,
  // the worker factorises for it, so the drag's first move refits as fast as the others.
  void prepareDrag(const Scene& scene, int sample);
  // The newest finished job not cancelled or superseded, once; nullopt otherwise.
  std::optional<FitJobResult> poll();
  // Discards the running and the pending job (their results never come back).
  void cancel();
  // Blocks until nothing is pending or running (tests, `render --ui`); true unless it timed out.
  bool waitIdle(double timeoutSeconds = 60);

  // From the next job on, the worker thread, the OpenMP team it starts and OpenBLAS's pool run
  // at nice value `nice` (background_priority.h; one-way: a lower value later changes nothing),
  // and, with `threads` > 0, the fits use that many OpenMP and OpenBLAS threads. The window sets
  // it (GuiApp); tests and `render --ui` leave the defaults (0: as the process started).
  // idle: SCHED_IDLE besides the nice value (idleCallingThread; one-way too).
  void setBackgroundPriority(int nice, int threads = 0, bool idle = false);

  bool busy() const;             // a job is running or pending
  bool hasResult() const;        // a finished job waits for poll()
  double runningMs() const;      // how long the current job has run (0 when idle)
  double progress() const;       // [0, 1) estimate of the running job
  std::uint64_t runningVersion() const;

 private:
  void loop();
  void applyPriority(int nice, int threads, bool idle);  // on the worker thread, between jobs

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  struct Job {
    Scene scene;
    std::optional<Scene> compare;
    std::uint64_t version = 0;
  };
  std::optional<Job> pending_;
  struct DragAnnouncement {
    Scene scene;
    int sample = 0;
  };
  std::optional<DragAnnouncement> pendingDrag_;  // done after any pending fit
  std::optional<FitJobResult> done_;
  bool running_ = false;
  std::uint64_t runningVersion_ = 0;
  std::uint64_t discardUpTo_ = 0;  // results of versions ≤ this are dropped
  // Set by cancel, a newer submit and the destructor while a job runs: the jobs that report
  // progress (hole filling) stop at their next report, the implicit fits at their next poll of
  // cancel_ (set at the same moments).
  std::atomic<bool> abandon_{false};
  CancelToken cancel_;
  std::chrono::steady_clock::time_point runningSince_;
  double estimateMs_ = 50;         // expected duration of the running job
  double lastMsPerCube_ = 0;       // last job: ms / (unknowns³), for the estimate
  bool stop_ = false;
  int wantedNice_ = 0, wantedThreads_ = 0;  // setBackgroundPriority
  bool wantedIdle_ = false;
  int appliedNice_ = 0, appliedThreads_ = 0;  // what the worker thread applied (its own)
  bool appliedIdle_ = false;
  std::unique_ptr<DragRefit> dragRefit_;  // used by the worker thread only
  std::thread thread_;
};

}  // namespace hermite::app
