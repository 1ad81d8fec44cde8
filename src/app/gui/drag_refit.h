#pragma once
// Fits of successive scenes that differ in one sample only — the GUI dragging a sample or
// turning its normal — through a kept factorisation (core/rbf/hrbf_bordered_refit.h): O(n²) per
// refit instead of the O(n³) fit from scratch (docs/performance.md, Drag refit).
//
// It applies to global HRBF fits of inline data without a transform; any other scene, a change
// of the fit settings, of the sample count or of two samples at once is fitted from scratch,
// and so is a drag whose bordered solve fails its accuracy check. The factorisation of the other
// samples' system (two to three fits from scratch) is made by prepare() when the GUI grabs the
// sample, else by the drag's first move.

#include <memory>
#include <optional>
#include <variant>

#include "app/gui/fit_worker.h"
#include "core/rbf/hrbf_bordered_refit.h"

namespace hermite::app {

class DragRefit {
 public:
  // The fit of `scene`: through the kept factorisation when `scene` differs from the last scene
  // fitted here in one sample only, else from scratch (fitOutcome, given `progress` and `cancel`).
  // Never throws.
  std::shared_ptr<const FitOutcome> fit(const Scene& scene, const std::function<bool(double)>& progress = {},
                                        const CancelToken* cancel = nullptr);

  // Factorises for a drag of `sample` about to begin (the GUI calls it when a sample is grabbed),
  // so that the first move is as quick as the next ones. `scene` must be the inline scene the
  // moves will edit. Never throws (a failure leaves the fits to decide).
  void prepare(const Scene& scene, int sample);

  // Fits that went through the bordered solve, and the factorisations it made (for tests).
  int borderedFits() const { return borderedFits_; }
  int factorisations() const { return factorisations_; }

 private:
  template <int Dim>
  std::shared_ptr<const FitOutcome> fitDim(const Scene& scene, const CancelToken* cancel);
  template <int Dim>
  void prepareDim(const Scene& scene, int sample);

  // The last scene fitted here, as samples and settings, and the drag's kept factorisation.
  template <int Dim>
  struct State {
    FitSpec fit;
    HermiteSamples<Dim> samples;
    std::unique_ptr<HrbfBorderedRefit<Dim>> drag;
  };
  std::variant<std::monostate, State<2>, State<3>> last_;
  int borderedFits_ = 0;
  int factorisations_ = 0;
};

}  // namespace hermite::app
