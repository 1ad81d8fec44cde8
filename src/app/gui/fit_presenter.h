#pragma once
// The fits on screen: submits the document's scene (and the compare scene) to the FitWorker when
// what a fit reads changed — the data, the fit settings, the transform, the patch or hole-filling
// document, the compare settings — and not for a view or camera change, which only redraws;
// adopts finished jobs, and keeps the last good result on screen while a newer one runs or after
// one failed.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/fit_worker.h"
#include "app/gui/gui_status.h"

namespace hermite::app {

// Compare: the right half of a split view shows the same data fitted another way.
enum class CompareWith { RbfOffset, Hrbf, OtherKernel, OtherRadius };
struct CompareSettings {
  bool enabled = false;
  CompareWith with = CompareWith::RbfOffset;
  KernelType kernel = KernelType::Gaussian;
  double radius = 0.5;
};

// The scene the right half fits: `scene` with the compared setting changed; none when compare is
// off or the mode has no implicit fit.
std::optional<Scene> compareScene(const Scene& scene, const CompareSettings& compare);

class FitPresenter {
 public:
  FitWorker& worker() { return worker_; }
  const FitWorker& worker() const { return worker_; }
  // The last good results (null before the first), the version the main one fitted.
  const std::shared_ptr<const FitOutcome>& shown() const { return shown_; }
  const std::shared_ptr<const FitOutcome>& shownCompare() const { return shownCompare_; }
  std::uint64_t shownVersion() const { return shownVersion_; }
  // The shown fit when it is of `mode`, else null: right after a mode switch (2D ⇄ 3D, patch,
  // hole filling) the previous mode's result stays on screen until the new fit arrives, and
  // tools that read samples must not take it for the current one.
  const FitOutcome* current(SceneMode mode) const {
    return shown_ && shown_->scene.mode == mode ? shown_.get() : nullptr;
  }
  const std::string& lastError() const { return lastError_; }  // of the last fit, empty when it succeeded

  // Queues a fit of version `version` of `scene` when its fit inputs (`fitInputs`:
  // ConcernVersions::fitInputs) or `compare` changed since the last submission; a version that
  // changed only the view or the camera takes the submitted fit as its own.
  // synchronous: waits for it (render --ui, tests); else a fit as quick as the last one is
  // waited for briefly, so it shows in this frame.
  void submitIfStale(const Scene& scene, std::uint64_t version, std::uint64_t fitInputs, const CompareSettings& compare,
                     bool synchronous);
  // Takes a finished job: its results go on screen, or its errors into `status`.
  void adoptFinished(GuiStatus& status);
  // Discards the running job; `version` is not resubmitted.
  void cancel(std::uint64_t version);
  // Jobs submitted to the worker (a view-only change submits none).
  int submissions() const { return submissions_; }

 private:
  FitWorker worker_;
  std::uint64_t submittedVersion_ = 0;  // the newest document version the submitted fit stands for
  std::uint64_t fittedVersion_ = 0;     // the version whose scene the worker fits
  std::uint64_t submittedFitInputs_ = 0;  // 0: nothing submitted yet
  bool submittedShown_ = false;  // the worker's result for fittedVersion_ is on screen
  CompareSettings submittedCompare_;
  int submissions_ = 0;
  std::shared_ptr<const FitOutcome> shown_, shownCompare_;
  std::uint64_t shownVersion_ = 0;
  std::string lastError_;
  double lastWallMs_ = 1e9;  // wall time of the last finished job (main + compare fits)
  std::shared_ptr<const FitOutcome> lastFinished_;  // that job's main fit (failed ones too)
  std::vector<std::string> loggedWarnings_;  // the warnings last written to the message log
};

}  // namespace hermite::app
