#include "app/gui/drag_refit.h"

#include <chrono>
#include <cstdint>

#include "scene/data_reach_mask.h"
#include "scene/scene_fit_memory.h"

namespace hermite::app {

namespace {

bool eligible(const Scene& scene) {
  return (scene.mode == SceneMode::Implicit2d || scene.mode == SceneMode::Implicit3d) &&
         scene.fit.method == FitMethod::Hrbf && scene.transform.isIdentity() && scene.data.isInline() &&
         !choosePartition(scene, std::int64_t(scene.data.points.size())).pu;
}

// The one sample whose point or normal differs, or −1 (none, or more than one).
template <int Dim>
int singleChangedSample(const HermiteSamples<Dim>& a, const HermiteSamples<Dim>& b) {
  if (a.size() != b.size()) return -1;
  int changed = -1;
  for (int i = 0; i < a.size(); ++i) {
    if (a.points.col(i) == b.points.col(i) && a.normals.col(i) == b.normals.col(i)) continue;
    if (changed >= 0) return -1;
    changed = i;
  }
  return changed;
}

HrbfOptions hrbfOptions(const FitSpec& f) { return {Kernel{f.kernel, f.radius}, f.polynomial, f.smoothing, f.solver}; }

}  // namespace

void DragRefit::prepare(const Scene& scene, int sample) {
  if (!eligible(scene)) return;
  if (scene.mode == SceneMode::Implicit2d)
    prepareDim<2>(scene, sample);
  else
    prepareDim<3>(scene, sample);
}

template <int Dim>
void DragRefit::prepareDim(const Scene& scene, int sample) {
  try {
    std::vector<std::string> warnings;
    HermiteSamples<Dim> samples = sceneSamples<Dim>(scene, warnings);
    const State<Dim>* last = std::get_if<State<Dim>>(&last_);
    if (last && last->fit == scene.fit && last->drag && last->drag->moved() == sample &&
        last->samples.points == samples.points && last->samples.normals == samples.normals)
      return;  // already factorised for this drag
    auto drag = std::make_unique<HrbfBorderedRefit<Dim>>(samples, hrbfOptions(scene.fit), sample);
    ++factorisations_;
    last_ = State<Dim>{scene.fit, std::move(samples), std::move(drag)};
  } catch (const std::exception&) {
    // Bad data or a singular rest system: the fits report it.
  }
}

std::shared_ptr<const FitOutcome> DragRefit::fit(const Scene& scene, const std::function<bool(double)>& progress,
                                                 const CancelToken* cancel) {
  if (!eligible(scene)) {
    last_ = std::monostate{};
    return fitOutcome(scene, progress, cancel);
  }
  return scene.mode == SceneMode::Implicit2d ? fitDim<2>(scene, cancel) : fitDim<3>(scene, cancel);
}

template <int Dim>
std::shared_ptr<const FitOutcome> DragRefit::fitDim(const Scene& scene, const CancelToken* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> dataWarnings;
  HermiteSamples<Dim> samples;
  try {
    samples = sceneSamples<Dim>(scene, dataWarnings);
  } catch (const std::exception&) {
    last_ = std::monostate{};
    return fitOutcome(scene, {}, cancel);  // says what is wrong with the data
  }
  auto fromScratch = [&] {
    last_ = State<Dim>{scene.fit, samples, nullptr};
    return fitOutcome(scene, {}, cancel);
  };
  State<Dim>* last = std::get_if<State<Dim>>(&last_);
  if (!last || !(last->fit == scene.fit)) return fromScratch();
  const int moved = singleChangedSample(last->samples, samples);
  if (moved < 0) return fromScratch();

  try {
    if (!last->drag || last->drag->moved() != moved) {
      // The other samples are those of the last fit (only `moved` differs from it).
      last->drag = std::make_unique<HrbfBorderedRefit<Dim>>(last->samples, hrbfOptions(scene.fit), moved);
      ++factorisations_;
    }
    SceneFit<Dim> fitted;
    fitted.model = std::make_unique<HrbfModel<Dim>>(
        last->drag->fit(samples.points.col(moved), samples.normals.col(moved), &fitted.report));
    fitted.samples = samples;
    fitted.data = samples;
    fitted.warnings = dataWarnings;
    fitted.warnings.insert(fitted.warnings.end(), fitted.report.warnings.begin(), fitted.report.warnings.end());
    maskBeyondDataReach<Dim>(scene, fitted);  // an edited scan keeps its reach while a sample is dragged
    auto out = std::make_shared<FitOutcome>();
    out->scene = scene;
    out->result = std::move(fitted);
    out->wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    last->samples = std::move(samples);
    ++borderedFits_;
    return out;
  } catch (const std::exception&) {
    // Singular rest system, inaccurate bordered solve: the fit from scratch decides and reports.
    return fromScratch();
  }
}

}  // namespace hermite::app
