#include "app/gui/frame_pacing.h"

namespace hermite::app {

bool FramePacing::due(double now, bool input, bool work, bool busy) const {
  if (input || work || followUps_ > 0) return true;
  return now - last_ >= (busy ? kBusyInterval : kIdleInterval);
}

void FramePacing::drawn(double now, bool input) {
  last_ = now;
  if (input) followUps_ = kFollowUpFrames;
  else if (followUps_ > 0) --followUps_;
}

}  // namespace hermite::app
