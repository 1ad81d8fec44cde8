#include "app/gui/refined_rows.h"

#include <algorithm>

namespace hermite::app {

void RefinedRows::start(std::uint64_t job) {
  if (job < current_) return;
  current_ = job;
  shown_ = 0;
  active_ = true;
}

RowRange RefinedRows::take(std::uint64_t job, int published, int height) {
  if (!active_ || job != current_) return {};
  const RowRange r{shown_, std::clamp(published, shown_, std::max(height, shown_))};
  shown_ = r.end;
  return r;
}

}  // namespace hermite::app
