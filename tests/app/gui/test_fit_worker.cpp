// Cancel that stops work (issue 18): the fit worker's cancel sets the running fit's CancelToken,
// and the cores are free within 200 ms — a partition-of-unity fit stops at its next box, a dense
// fit at its next factorisation tile — while nothing of the cancelled fit comes back.

#include <doctest/doctest.h>

#include <chrono>
#include <optional>
#include <thread>

#include "app/gui/fit_worker.h"
#include "core/base/ms_since.h"
#include "core/points/hermite_samples.h"

using namespace hermite;
using namespace hermite::app;

namespace {

Scene sphere(int count, bool partition) {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = count;
  s.fit.partition.enabled = partition ? PartitionSwitch::On : PartitionSwitch::Off;
  return s;
}

// Submits `scene`, waits until it has run `runMs`, cancels it; the ms until the worker is idle.
double cancelAfter(FitWorker& worker, const Scene& scene, double runMs) {
  worker.submit(scene, 7);
  while (worker.runningMs() < runMs && worker.busy()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  REQUIRE(worker.busy());  // still fitting: the cancel interrupts it
  const auto t0 = std::chrono::steady_clock::now();
  worker.cancel();
  REQUIRE(worker.waitIdle(30));
  return msSince(t0);
}

}  // namespace

TEST_CASE("fit worker: Cancel stops a partition-of-unity fit box by box within 200 ms") {
  FitWorker worker;
  // 40 000 samples, 20 per box: a few thousand local fits, seconds of work on two cores.
  const double ms = cancelAfter(worker, sphere(40000, true), 300);
  CHECK(ms < 200);
  CHECK(!worker.poll());  // the cancelled fit never comes back
}

TEST_CASE("fit worker: Cancel stops a large dense fit within 200 ms") {
  // The factorisation of 6 000 unknowns polls the token between panels (dense_solver.h).
  FitWorker worker;
  const double ms = cancelAfter(worker, sphere(1500, false), 400);
  CHECK(ms < 200);
  CHECK(!worker.poll());
}

TEST_CASE("fitOutcome: a set token gives a cancelled outcome, not an error of the fit") {
  CancelToken token;
  token.cancel();
  const auto out = fitOutcome(sphere(200, false), {}, &token);
  CHECK(out->cancelled);
  CHECK(!out->ok());
  const auto pu = fitOutcome(sphere(2000, true), {}, &token);
  CHECK(pu->cancelled);
  token.reset();
  CHECK(fitOutcome(sphere(200, false), {}, &token)->ok());
}

// The panels read a fit's residuals and mean spacing in every frame: the worker computes them
// before it hands the fit over, so that the GUI thread finds them ready (a dense fit's residuals
// evaluate the model at every sample: seconds per frame at 5 000 samples).
TEST_CASE("fit worker: a finished fit comes with its residuals and mean spacing computed") {
  FitWorker worker;
  const Scene scene = sphere(200, false);
  worker.submit(scene, 3);
  REQUIRE(worker.waitIdle(60));
  const std::optional<FitJobResult> r = worker.poll();
  REQUIRE(r);
  REQUIRE(r->main->ok());
  const FitOutcome& fit = *r->main;
  REQUIRE(fit.residuals_.has_value());
  REQUIRE(fit.sampleSpacing_.has_value());
  const SceneFit<3>& f = *fit.as<SceneFit<3>>();
  const FitResiduals direct = fitResiduals(f);
  CHECK(fit.residuals().maxAbsF == direct.maxAbsF);
  CHECK(fit.residuals().maxGradError == direct.maxGradError);
  CHECK(fit.residuals().maxAbsF < 1e-6);  // an interpolating HRBF: f(pᵢ) = 0 up to rounding
  CHECK(fit.sampleSpacing() == meanSampleSpacing<3>(f.samples.points));
  CHECK(fit.sampleSpacing() > 0);
}
