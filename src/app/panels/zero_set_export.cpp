#include "app/panels/zero_set_export.h"

#include <exception>
#include <utility>

#include "app/commands/commands.h"
#include "app/gui/background_priority.h"
#include "app/gui/fit_worker.h"

namespace hermite::app {

ZeroSetExport::~ZeroSetExport() {
  cancel_.cancel();
  join();
}

void ZeroSetExport::join() {
  if (thread_.joinable()) thread_.join();
}

bool ZeroSetExport::start(std::shared_ptr<const FitOutcome> fit, const std::string& path) {
  if (running_.load()) return false;
  join();  // the finished thread of the last export
  cancel_.reset();
  running_.store(true);
  thread_ = std::thread([this, fit = std::move(fit), path] {
    lowerViewWorkerPriority();  // below the frames, like the view's bakes (its OpenMP team inherits it)
    Result r;
    try {
      const int resolution = autoMeshResolution(fit->scene.dimension(), fit->dataCount());
      r.message = exportZeroSet(*fit, path, resolution, kDefaultChordTolerance, &cancel_);
      r.ok = true;
    } catch (const Cancelled&) {
      r.message = "export of " + path + " cancelled";
    } catch (const std::exception& e) {
      r.message = e.what();
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      result_ = std::move(r);
    }
    running_.store(false);
  });
  return true;
}

bool ZeroSetExport::hasResult() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return result_.has_value();
}

std::optional<ZeroSetExport::Result> ZeroSetExport::take() {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::optional<Result> r = std::move(result_);
  result_.reset();
  return r;
}

}  // namespace hermite::app
