#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "core/base/memory_check.h"
#include "scene/scene_fit.h"
#include "scene/scene_fit_memory.h"

using namespace hermite;

namespace {

Scene sphereScene(int count, const char* partition) {
  const std::string text = R"({"version": 1, "mode": "implicit3d", "data": {"preset": "sphere", "count": )" +
                           std::to_string(count) + R"(}, "fit": {"partition": {"enabled": )" + partition + "}}}";
  return parseScene(nlohmann::json::parse(text), "s.json", ".");
}

const AvailableMemory kPlenty{std::uint64_t{1} << 40, "test limit"};  // 1 TiB

}  // namespace

TEST_CASE("fit.partition.enabled \"auto\": dense up to 10 000 unknowns, partition of unity above") {
  // HRBF 3D with a linear term: n = 4·N + 4.
  CHECK(sceneDenseUnknowns(sphereScene(2499, "\"auto\""), 2499) == 10000);
  const PartitionChoice small = choosePartition(sphereScene(2499, "\"auto\""), 2499, kPlenty);
  CHECK_FALSE(small.pu);
  CHECK(small.message.empty());
  const PartitionChoice big = choosePartition(sphereScene(2500, "\"auto\""), 2500, kPlenty);
  CHECK(big.pu);
  CHECK(big.message == "fit.partition.enabled \"auto\": 2500 samples make a global fit of 10004 unknowns, more "
                       "than 10000: fitted by partition of unity");
  // Explicit switches keep their meaning whatever the size.
  CHECK(choosePartition(sphereScene(2500, "false"), 2500, kPlenty).pu == false);
  CHECK(choosePartition(sphereScene(10, "true"), 10, kPlenty).pu == true);
  // RBF-offset has no partition of unity: "auto" is global.
  Scene offset = sphereScene(5000, "\"auto\"");
  offset.fit.method = FitMethod::RbfOffset;
  CHECK_FALSE(choosePartition(offset, 5000, kPlenty).pu);
}

TEST_CASE("fit.partition.enabled \"auto\": a small fit that needs half the memory or more is partition of unity") {
  // 2 000 samples: 8 004 unknowns, within the count; the memory decides, at half of what is available.
  const Scene s = sphereScene(2000, "\"auto\"");
  const PlannedAllocation plan = *sceneFitPlan(s, 2000);
  const PartitionChoice roomy = choosePartition(s, 2000, AvailableMemory{2 * plan.bytes + 2, "test limit"});
  CHECK_FALSE(roomy.pu);
  const PartitionChoice tight = choosePartition(s, 2000, AvailableMemory{2 * plan.bytes - 1, "test limit"});
  CHECK(tight.pu);
  CHECK(tight.message.find("8004 unknowns") != std::string::npos);
  CHECK(tight.message.find("available (test limit)") != std::string::npos);
  CHECK(tight.message.find("fitted by partition of unity") != std::string::npos);
}

TEST_CASE("fitScene follows the choice and says so in its warnings") {
  const SceneFit<3> dense = fitScene<3>(sphereScene(300, "\"auto\""));
  CHECK(dense.pu() == nullptr);
  const SceneFit<3> pu = fitScene<3>(sphereScene(3000, "\"auto\""));
  REQUIRE(pu.pu() != nullptr);
  REQUIRE_FALSE(pu.warnings.empty());
  CHECK(pu.warnings.front().find("fitted by partition of unity") != std::string::npos);
  // The written scene keeps "auto".
  CHECK(sceneToJson(sphereScene(3000, "\"auto\""))["fit"]["partition"]["enabled"] == "auto");
  CHECK(sceneToJson(sphereScene(3000, "false"))["fit"]["partition"]["enabled"] == false);
  CHECK(sceneToJson(sphereScene(3000, "true"))["fit"]["partition"]["enabled"] == true);
}
