#include "app/gui/fit_worker.h"

#include <chrono>
#include <cmath>
#include <type_traits>

#include "app/gui/background_priority.h"
#include "app/gui/drag_refit.h"
#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/base/threading.h"
#include "core/points/hermite_samples.h"
#include "scene/data_reach_mask.h"
#include "scene/degenerate_check.h"

namespace hermite::app {

namespace {

// Samples of the scene without fitting (for the duration estimate): inline data only, else 0.
double sampleCount(const Scene& s) { return s.data.isInline() ? double(s.data.points.size()) : 0.0; }

std::shared_ptr<const FitOutcome> failedOutcome(const Scene& scene, std::string error) {
  auto out = std::make_shared<FitOutcome>();
  out->scene = scene;
  out->error = std::move(error);
  return out;
}

}  // namespace

std::shared_ptr<const FitOutcome> fitOutcomeOrThrow(const Scene& scene, const std::function<bool(double)>& progress,
                                                    const CancelToken* cancel) {
  auto out = std::make_shared<FitOutcome>();
  out->scene = scene;
  const auto t0 = std::chrono::steady_clock::now();
  if (scene.mode == SceneMode::Implicit2d) {
    SceneFit<2> fit = fitScene<2>(scene, cancel);
    checkDegenerateField<2>(scene, fit);
    maskBeyondDataReach<2>(scene, fit);
    out->result = std::move(fit);
  } else if (scene.mode == SceneMode::Implicit3d) {
    SceneFit<3> fit = fitScene<3>(scene, cancel);
    checkDegenerateField<3>(scene, fit);
    maskBeyondDataReach<3>(scene, fit);
    out->result = std::move(fit);
  }
  else if (scene.mode == SceneMode::Patch)
    out->result = buildPatchDisplay(scene.patch);
  else
    out->result = runHoleFillStages(scene.holefill, progress);
  out->wallMs = msSince(t0);
  return out;
}

std::shared_ptr<const FitOutcome> fitOutcome(const Scene& scene, const std::function<bool(double)>& progress,
                                             const CancelToken* cancel) {
  try {
    return fitOutcomeOrThrow(scene, progress, cancel);
  } catch (const Cancelled& e) {
    auto out = std::make_shared<FitOutcome>();
    out->scene = scene;
    out->error = e.what();
    out->cancelled = true;
    return out;
  } catch (const InputError& e) {
    return failedOutcome(scene, std::string("input: ") + e.what());
  } catch (const NumericalError& e) {
    return failedOutcome(scene, std::string("numerical failure: ") + e.what());
  } catch (const std::bad_alloc&) {
    return failedOutcome(scene, "out of memory");
  } catch (const std::exception& e) {
    return failedOutcome(scene, e.what());
  }
}

const SceneFitReport* FitOutcome::implicitFit() const {
  const SceneFitReport* r = nullptr;
  visitImplicit([&](const auto& f) { r = &f; });
  return r;
}

int FitOutcome::dataCount() const {
  int n = 0;
  visitImplicit([&](const auto& f) { n = f.data.size(); });
  return n;
}

double FitOutcome::sampleSpacing() const {
  if (!sampleSpacing_) {
    sampleSpacing_ = 0.0;
    visitImplicit([&](const auto& f) {
      sampleSpacing_ = meanSampleSpacing<std::decay_t<decltype(f)>::kDim>(f.samples.points);
    });
  }
  return *sampleSpacing_;
}

const FitResiduals& FitOutcome::residuals() const {
  if (!residuals_) {
    residuals_ = FitResiduals{};
    if (ok()) visitImplicit([&](const auto& f) { residuals_ = fitResiduals(f); });
  }
  return *residuals_;
}

const std::vector<std::string>& FitOutcome::warnings() const {
  static const std::vector<std::string> none;
  const SceneFitReport* r = implicitFit();
  return r ? r->warnings : none;
}

FitWorker::FitWorker() : dragRefit_(std::make_unique<DragRefit>()), thread_([this] { loop(); }) {}

FitWorker::~FitWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    pending_.reset();
    abandon_ = true;
    cancel_.cancel();
  }
  wake_.notify_all();
  thread_.join();  // a running fit stops at its next poll of cancel_
}

void FitWorker::submit(const Scene& scene, std::uint64_t version, std::optional<Scene> compare) {
  {
    std::lock_guard lock(mutex_);
    pending_ = Job{scene, std::move(compare), version};
    if (running_) abandon_ = true, cancel_.cancel();
  }
  wake_.notify_all();
}

void FitWorker::prepareDrag(const Scene& scene, int sample) {
  {
    std::lock_guard lock(mutex_);
    pendingDrag_ = DragAnnouncement{scene, sample};
  }
  wake_.notify_all();
}

std::optional<FitJobResult> FitWorker::poll() {
  std::lock_guard lock(mutex_);
  std::optional<FitJobResult> r = std::move(done_);
  done_.reset();
  return r;
}

void FitWorker::cancel() {
  std::lock_guard lock(mutex_);
  pending_.reset();
  done_.reset();
  if (running_) discardUpTo_ = std::max(discardUpTo_, runningVersion_), abandon_ = true, cancel_.cancel();
}

bool FitWorker::waitIdle(double timeoutSeconds) {
  std::unique_lock lock(mutex_);
  return idle_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds), [&] { return !running_ && !pending_; });
}

void FitWorker::setBackgroundPriority(int nice, int threads, bool idle) {
  std::lock_guard lock(mutex_);
  wantedNice_ = nice;
  wantedThreads_ = threads;
  wantedIdle_ = idle;
}

bool FitWorker::busy() const {
  std::lock_guard lock(mutex_);
  return running_ || pending_.has_value();
}

bool FitWorker::hasResult() const {
  std::lock_guard lock(mutex_);
  return done_.has_value();
}

double FitWorker::runningMs() const {
  std::lock_guard lock(mutex_);
  return running_ ? msSince(runningSince_) : 0.0;
}

double FitWorker::progress() const {
  std::lock_guard lock(mutex_);
  if (!running_) return 0.0;
  // Approaches 1 without reaching it, linear while within the estimate.
  const double x = msSince(runningSince_) / std::max(estimateMs_, 1.0);
  return x < 0.9 ? x : 1.0 - 0.1 * std::exp(-(x - 0.9) * 4);
}

std::uint64_t FitWorker::runningVersion() const {
  std::lock_guard lock(mutex_);
  return running_ ? runningVersion_ : 0;
}

void FitWorker::applyPriority(int nice, int threads, bool idle) {
  if (nice > appliedNice_) {
    // Before the job's first parallel loop, so that the OpenMP team this thread starts inherits it.
    appliedNice_ = lowerCallingThreadPriority(nice);
    lowerBlasPoolPriority(nice);
  }
  if (idle && !appliedIdle_) {
    appliedIdle_ = idleCallingThread();
    idleBlasPool();
  }
  if (threads > 0 && threads != appliedThreads_) setThreadCount(threads), appliedThreads_ = threads;
}

void FitWorker::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || pending_.has_value() || pendingDrag_.has_value(); });
    if (stop_) return;
    if (!pending_) {
      DragAnnouncement drag = std::move(*pendingDrag_);
      pendingDrag_.reset();
      lock.unlock();
      dragRefit_->prepare(drag.scene, drag.sample);
      lock.lock();
      continue;
    }
    Job job = std::move(*pending_);
    pending_.reset();
    running_ = true;
    abandon_ = false;
    cancel_.reset();
    runningVersion_ = job.version;
    runningSince_ = std::chrono::steady_clock::now();
    const double n = sampleCount(job.scene) * (job.scene.dimension() + 1);
    estimateMs_ = lastMsPerCube_ > 0 && n > 0 ? lastMsPerCube_ * n * n * n : 200.0;
    const int nice = wantedNice_, threads = wantedThreads_;
    const bool idle = wantedIdle_;
    lock.unlock();

    applyPriority(nice, threads, idle);
    FitJobResult result;
    result.version = job.version;
    result.main = dragRefit_->fit(job.scene, [this](double) { return !abandon_; }, &cancel_);
    if (job.compare && !result.main->cancelled) result.compare = fitOutcome(*job.compare, {}, &cancel_);
    // What the panels show of the fits, here rather than on the GUI thread (FitOutcome).
    for (const auto* fit : {result.main.get(), result.compare.get()})
      if (fit && fit->ok()) {
        fit->sampleSpacing();
        fit->residuals();
      }

    lock.lock();
    running_ = false;
    if (n > 0 && result.main->ok()) lastMsPerCube_ = std::max(result.main->wallMs, 1.0) / (n * n * n);
    const bool superseded = pending_.has_value() && pending_->version > job.version;
    if (job.version > discardUpTo_ && !superseded) done_ = std::move(result);
    if (!pending_) idle_.notify_all();
  }
}

}  // namespace hermite::app
