#include <doctest/doctest.h>

#include <filesystem>

#include "scene/scene_file.h"
#include "scene/scene_fit.h"

using namespace hermite;

// Every scene in assets/scenes loads and fits; ill-conditioned ones still fit and carry their
// warning (that is their lesson); the well-conditioned ones interpolate.
TEST_CASE("every teaching scene in assets/scenes loads and fits") {
  namespace fs = std::filesystem;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(HERMITE_SOURCE_DIR) / "assets" / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const std::string path = entry.path().string();
    CAPTURE(path);
    const Scene scene = loadSceneFile(path);
    // Round trip through the complete document.
    const Scene again = parseScene(sceneToJson(scene), path, entry.path().parent_path().string());
    CHECK(sceneToJson(again) == sceneToJson(scene));
    auto check = [&](const auto& fit, const auto& samples) {
      // A global fit or a partition of unity (fit.partition), never an empty model.
      CHECK(std::visit([](const auto& m) { return m != nullptr; }, fit.model));
      CHECK(fit.report.nSamples == samples.size());
      Eigen::VectorXd f;
      fit.field().evaluateBatch(samples.points, f);
      CHECK(f.allFinite());
      const bool illConditioned = fit.report.conditionEstimate > 1e12;
      bool warned = false;
      for (const std::string& w : fit.warnings) warned |= w.find("ill-conditioned") != std::string::npos;
      CHECK(warned == illConditioned);
      if (fit.report.conditionEstimate < 1e8) CHECK(f.cwiseAbs().maxCoeff() <= 1e-6);
    };
    if (scene.dimension() == 2) {
      const SceneFit<2> fit = fitScene<2>(scene);
      check(fit, fit.samples);
    } else {
      const SceneFit<3> fit = fitScene<3>(scene);
      check(fit, fit.samples);
    }
  }
  CHECK(count >= 30);
}
