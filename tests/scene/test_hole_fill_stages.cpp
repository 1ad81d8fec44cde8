// The hole-filling pipeline stopped at each stage (the GUI's holefill mode), on the built-in
// holed meshes.

#include <doctest/doctest.h>

#include <vector>

#include "core/base/errors.h"
#include "scene/hole_fill_stages.h"

using namespace hermite;

TEST_CASE("holefill stages: the presets have their holes; every stage closes them, projection onto the implicit") {
  for (const auto& [preset, holes] : {std::pair{std::string("torus"), 3}, std::pair{std::string("sphere"), 2}}) {
    CAPTURE(preset);
    const TriMesh input = holeFillPresetMesh(preset);
    CHECK(checkMesh(input).boundaryEdges > 0);
    HoleFillSpec spec;
    spec.preset = preset;
    spec.stage = HoleFillStage::Holes;
    const HoleFillStages detected = runHoleFillStages(spec);
    CHECK(int(detected.holes.size()) == holes);
    CHECK(detected.trianglesAdded == 0);
    for (HoleFillStage stage : {HoleFillStage::Front, HoleFillStage::Fair, HoleFillStage::Project}) {
      CAPTURE(holeFillStageName(stage));
      spec.stage = stage;
      const HoleFillStages s = runHoleFillStages(spec);
      for (const auto& h : s.holes) CHECK_MESSAGE(h.filled, (h.notes.empty() ? "" : h.notes.front()));
      CHECK(s.trianglesAdded > 0);
      const MeshCheck c = checkMesh(s.result);
      CHECK(c.closedManifold());
      if (stage == HoleFillStage::Project) {
        CHECK(s.unconverged == 0);
        CHECK(s.maxAbsF < 1e-6);
        for (const auto& h : s.holes) CHECK(h.ringPoints.cols() > 0);
      }
    }
  }
  HoleFillSpec bad;
  bad.preset = "cube";
  CHECK_THROWS_AS(runHoleFillStages(bad), InputError);
}

TEST_CASE("holefill stages: progress rises to 1, and a false from it leaves the remaining holes cancelled") {
  HoleFillSpec spec;  // the torus preset
  std::vector<double> fractions;
  const HoleFillStages all = runHoleFillStages(spec, [&](double f) { return fractions.push_back(f), true; });
  REQUIRE(all.holes.size() >= 2);
  REQUIRE(!fractions.empty());
  for (std::size_t k = 1; k < fractions.size(); ++k) CHECK(fractions[k] >= fractions[k - 1] - 1e-12);
  CHECK(fractions.back() <= 1.0);
  for (const HoleFillStageHole& h : all.holes) CHECK(h.filled);

  const HoleFillStages stopped = runHoleFillStages(spec, [](double) { return false; });
  REQUIRE(stopped.holes.size() == all.holes.size());
  for (const HoleFillStageHole& h : stopped.holes) {
    CHECK_FALSE(h.filled);
    CHECK(h.cancelled);
    CHECK(h.reason == "cancelled");
    CHECK(h.loop.size() > 0);
  }
  CHECK(stopped.trianglesAdded == 0);
}
