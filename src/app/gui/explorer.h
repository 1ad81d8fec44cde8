#pragma once
// The r-sensitivity explorer's background work (the "Explore r" panel): the document's data and
// fit settings refitted at k log-spaced radii on a thread of its own, each finished radius kept
// with its model (for the thumbnail the main thread draws) and its diagnostics row (condition,
// residuals, leave-one-out error). A new run cancels the previous one between radii.

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "app/gui/fit_worker.h"
#include "scene/radius_sweep.h"

namespace hermite::app {

struct ExplorerEntry {
  RadiusSweepRow row;
  std::shared_ptr<const FitOutcome> fit;  // the model at this radius (null when it failed)
};

class RadiusExplorer {
 public:
  RadiusExplorer() = default;
  ~RadiusExplorer();
  RadiusExplorer(const RadiusExplorer&) = delete;
  RadiusExplorer& operator=(const RadiusExplorer&) = delete;

  // Starts a sweep of `scene` over `radii` (cancelling a running one).
  void start(const Scene& scene, std::vector<double> radii);
  void cancel();
  bool running() const { return running_.load(); }
  float progress() const { return progress_.load(); }
  // Entries finished so far, in radius order (a copy: the worker appends concurrently).
  std::vector<ExplorerEntry> entries() const;
  // Bumped whenever an entry is added (the panel redraws thumbnails when it moves).
  int generation() const { return generation_.load(); }
  // Blocks until the sweep finishes (tests, `sweep`).
  void wait();

  // Editable settings of the panel.
  int count = 6;
  double lower = 0.05, upper = 2.0;

 private:
  void join();
  std::thread thread_;
  std::atomic<bool> cancel_{false}, running_{false};
  std::atomic<float> progress_{0};
  std::atomic<int> generation_{0};
  mutable std::mutex mutex_;
  std::vector<ExplorerEntry> entries_;
};

}  // namespace hermite::app
