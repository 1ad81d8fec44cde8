#pragma once
// Which rows of a progressive exact refinement the GL thread copies into the view next
// (docs/design.md, Progressive 3D view). The view worker refines a settled view band by band and
// publishes how many rows (from the top) are final; each frame the GL thread copies the rows it
// has not shown yet. The newest view wins: once a refinement for a newer view starts, rows that a
// superseded job publishes are dropped, whenever they arrive.

#include <cstdint>

namespace hermite::app {

// A range of image rows [begin, end), row 0 = top.
struct RowRange {
  int begin = 0, end = 0;
  bool empty() const { return end <= begin; }
  bool operator==(const RowRange&) const = default;
};

class RefinedRows {
 public:
  // The refinement of job `job` (a number that grows with each submission) starts: nothing of it
  // is shown yet, and rows of earlier jobs are dropped from now on. An older `job` changes nothing.
  void start(std::uint64_t job);
  // Job `job` has published rows [0, published): the rows to copy now (those not shown yet, at
  // most `height`), marked as shown; empty when the job is not the newest started or nothing is new.
  RowRange take(std::uint64_t job, int published, int height);
  // Every row of job `job`'s image (`height` rows) is shown.
  bool complete(std::uint64_t job, int height) const { return job == current_ && active_ && shown_ >= height; }
  // Job `job` has published rows that take() would return.
  bool waiting(std::uint64_t job, int published) const { return job == current_ && active_ && published > shown_; }
  // No refinement is shown in rows any more (the view moved on).
  void clear() { active_ = false; }
  bool active() const { return active_; }
  std::uint64_t current() const { return current_; }

 private:
  std::uint64_t current_ = 0;
  int shown_ = 0;
  bool active_ = false;
};

}  // namespace hermite::app
