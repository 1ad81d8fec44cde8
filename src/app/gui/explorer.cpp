#include "app/gui/explorer.h"

#include "scene/scene_fit.h"

namespace hermite::app {

RadiusExplorer::~RadiusExplorer() { cancel(); }

void RadiusExplorer::join() {
  if (thread_.joinable()) thread_.join();
}

void RadiusExplorer::cancel() {
  cancel_ = true;
  join();
  cancel_ = false;
}

void RadiusExplorer::wait() { join(); }

std::vector<ExplorerEntry> RadiusExplorer::entries() const {
  std::lock_guard lock(mutex_);
  return entries_;
}

void RadiusExplorer::start(const Scene& scene, std::vector<double> radii) {
  cancel();
  {
    std::lock_guard lock(mutex_);
    entries_.clear();
  }
  ++generation_;
  progress_ = 0;
  running_ = true;
  thread_ = std::thread([this, scene, radii = std::move(radii)] {
    double spacing = 0;
    try {
      std::vector<std::string> warnings;
      spacing = scene.dimension() == 2 ? meanSampleSpacing<2>(sceneSamples<2>(scene, warnings).points)
                                       : meanSampleSpacing<3>(sceneSamples<3>(scene, warnings).points);
    } catch (const std::exception&) {
      // Each radius reports the data error itself.
    }
    for (std::size_t k = 0; k < radii.size() && !cancel_; ++k) {
      Scene s = scene;
      s.fit.radius = radii[k];
      ExplorerEntry e;
      auto fit = fitOutcome(s);
      if (fit->ok()) {
        fit->visitImplicit([&](const auto& f) { e.row = radiusSweepRow(s, f, spacing); });
        e.fit = std::move(fit);
      } else {
        e.row.radius = radii[k];
        e.row.error = fit->error;
      }
      {
        std::lock_guard lock(mutex_);
        entries_.push_back(std::move(e));
      }
      progress_ = float(k + 1) / float(radii.size());
      ++generation_;
    }
    running_ = false;
  });
}

}  // namespace hermite::app
