// The Data section's "Export mesh" (zero_set_export.h): it runs on its own thread and hands over
// the summary line of `hermite-lab mesh` with its defaults once, one export at a time; a cancel
// ends it within a batch of evaluations; bad outputs come back as errors.

#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include "app/gui/fit_worker.h"
#include "app/panels/zero_set_export.h"
#include "support/temp_dir.h"

using namespace hermite;
using namespace hermite::app;

namespace {

std::shared_ptr<const FitOutcome> sphereFit(int count) {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = count;
  return fitOutcomeOrThrow(s);
}

// Waits up to `seconds` for the export's result.
std::optional<ZeroSetExport::Result> waitForResult(ZeroSetExport& e, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (std::optional<ZeroSetExport::Result> r = e.take()) return r;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return std::nullopt;
}

}  // namespace

TEST_CASE("zero-set export: runs off the calling thread and hands over mesh's summary once") {
  const auto fit = sphereFit(200);
  const hermite::testing::TempDir dir("zero_set_export");
  const std::string out = dir.file("sphere.ply");
  ZeroSetExport e;
  CHECK_FALSE(e.hasResult());
  REQUIRE(e.start(fit, out));
  CHECK_FALSE(e.start(fit, out));  // one at a time
  const std::optional<ZeroSetExport::Result> r = waitForResult(e, 60);
  REQUIRE(r.has_value());
  CHECK(r->ok);
  CHECK(r->message.rfind("mesh: ", 0) == 0);
  CHECK(r->message.find("closed manifold") != std::string::npos);
  CHECK(r->message.find("edges split by chord refinement") != std::string::npos);  // mesh's default
  CHECK(std::filesystem::file_size(out) > 0);
  CHECK_FALSE(e.running());
  CHECK_FALSE(e.take().has_value());  // once
  REQUIRE(e.start(fit, out));  // and again
  CHECK(waitForResult(e, 60).has_value());
}

TEST_CASE("zero-set export: an output it cannot write comes back as an error") {
  ZeroSetExport e;
  REQUIRE(e.start(sphereFit(100), "/nonexistent-dir/zero-set.ply"));
  const std::optional<ZeroSetExport::Result> r = waitForResult(e, 60);
  REQUIRE(r.has_value());
  CHECK_FALSE(r->ok);
  CHECK(r->message.find("/nonexistent-dir") != std::string::npos);
}

TEST_CASE("zero-set export: cancel ends it and says so") {
  ZeroSetExport e;
  const auto fit = sphereFit(3000);
  const hermite::testing::TempDir dir("zero_set_export");
  REQUIRE(e.start(fit, dir.file("cancel.ply")));
  e.cancel();
  const auto t0 = std::chrono::steady_clock::now();
  const std::optional<ZeroSetExport::Result> r = waitForResult(e, 5);
  REQUIRE(r.has_value());
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0);
  CHECK_FALSE(r->ok);
  CHECK(r->message.find("cancelled") != std::string::npos);
}
