#include "app/gui/fit_presenter.h"

namespace hermite::app {

namespace {

// A fit expected to take less than this (the last one did) is waited for within the frame that
// submitted it (ms).
constexpr double kSameFrameFitMs = 12.0;

bool sameCompare(const CompareSettings& a, const CompareSettings& b) {
  return a.enabled == b.enabled &&
         (!a.enabled || (a.with == b.with && a.kernel == b.kernel && a.radius == b.radius));
}

// Whether `scene` fits as many samples as `last` did. Only then is its fit expected to be as
// quick as the last one: a drag moves samples, while opening or generating other data (50 samples
// before, 1 500 now) changes the cost by orders of magnitude.
bool sameSampleCount(const Scene& scene, const FitOutcome& last) {
  const DataSpec& d = scene.data;
  const DataSpec& l = last.scene.data;
  if (d.isInline()) return std::int64_t(d.points.size()) == std::int64_t(last.dataCount());
  return !l.isInline() && d.preset == l.preset && d.count == l.count && d.resolvedFile == l.resolvedFile;
}

}  // namespace

std::optional<Scene> compareScene(const Scene& s, const CompareSettings& compare) {
  if (!compare.enabled || (s.mode != SceneMode::Implicit2d && s.mode != SceneMode::Implicit3d)) return std::nullopt;
  Scene c = s;
  switch (compare.with) {
    case CompareWith::RbfOffset: c.fit.method = FitMethod::RbfOffset; break;
    case CompareWith::Hrbf: c.fit.method = FitMethod::Hrbf; break;
    case CompareWith::OtherKernel: c.fit.kernel = compare.kernel; break;
    case CompareWith::OtherRadius: c.fit.radius = compare.radius; break;
  }
  return c;
}

void FitPresenter::submitIfStale(const Scene& scene, std::uint64_t version, std::uint64_t fitInputs,
                                 const CompareSettings& compare, bool synchronous) {
  if (version == submittedVersion_ && sameCompare(compare, submittedCompare_)) return;
  if (fitInputs == submittedFitInputs_ && sameCompare(compare, submittedCompare_)) {
    // Only the view changed: the submitted fit (shown or still running) stands for this version.
    if (submittedShown_) shownVersion_ = version;
    submittedVersion_ = version;
    return;
  }
  submittedVersion_ = fittedVersion_ = version;
  submittedShown_ = false;
  submittedCompare_ = compare;
  submittedFitInputs_ = fitInputs;
  ++submissions_;
  worker_.submit(scene, version, compareScene(scene, compare));
  if (synchronous)
    worker_.waitIdle(600);
  else if (lastWallMs_ < kSameFrameFitMs && lastFinished_ && sameSampleCount(scene, *lastFinished_))
    // Fits as quick as the last one (a drag's bordered refits) show in this very frame: one
    // short wait instead of a frame of latency. Slower ones stay on the worker.
    worker_.waitIdle(kSameFrameFitMs / 1000.0);
}

void FitPresenter::adoptFinished(GuiStatus& status) {
  std::optional<FitJobResult> r = worker_.poll();
  if (!r) return;
  lastWallMs_ = r->main->wallMs + (r->compare ? r->compare->wallMs : 0.0);
  lastFinished_ = r->main;
  if (r->main->ok()) {
    shown_ = r->main;
    // The versions since that changed only the view show this fit too.
    submittedShown_ = r->version == fittedVersion_;
    shownVersion_ = submittedShown_ ? submittedVersion_ : r->version;
    lastError_.clear();
    // The log gets a fit's warnings once, not again for every refit that repeats them (a drag).
    if (r->main->warnings() != loggedWarnings_) {
      loggedWarnings_ = r->main->warnings();
      for (const std::string& w : loggedWarnings_) status.append(Severity::Warning, w);
    }
  } else {
    // Keep the last good model on screen and say why the new one is not there.
    lastError_ = r->main->error;
    status.set("fit failed: " + r->main->error, true);
  }
  shownCompare_ = r->compare && r->compare->ok() ? r->compare : nullptr;
  if (r->compare && !r->compare->ok()) status.set("compare fit failed: " + r->compare->error, true);
}

void FitPresenter::cancel(std::uint64_t version) {
  worker_.cancel();
  submittedVersion_ = version;  // do not resubmit what was cancelled
}

}  // namespace hermite::app
