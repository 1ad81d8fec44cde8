#include "app/commands/kept_until_exit.h"

#include <atomic>
#include <mutex>
#include <vector>

namespace hermite::app {

namespace {

std::atomic<bool> enabled{false};

}  // namespace

void enableKeepUntilExit() { enabled = true; }

void keepUntilExit(std::shared_ptr<const void> object) {
  if (!enabled) return;  // `object` is released here
  static std::mutex mutex;
  // Never destroyed: a static vector's destructor would free its objects at exit, one by one.
  static auto* const kept = new std::vector<std::shared_ptr<const void>>();
  const std::lock_guard<std::mutex> lock(mutex);
  kept->push_back(std::move(object));
}

}  // namespace hermite::app
