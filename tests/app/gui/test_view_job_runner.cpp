// The view's background worker (issue 18, nothing slow on the UI thread): jobs run off the
// calling thread, the newest wins (the running one is cancelled through its token and nothing of
// it comes back), a coarse job may be let finish, and errors reach the GL step.

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "app/gui/view_job_runner.h"
#include "core/base/errors.h"
#include "core/base/ms_since.h"

using namespace hermite;
using namespace hermite::app;

namespace {

// A job that polls its token every ms for up to `ms`, then returns a step that stores `value`.
ViewJobRunner::Job polling(int ms, int value, int& out, std::atomic<bool>& started) {
  return [ms, value, &out, &started](const CancelToken& cancel) -> ViewJobRunner::Apply {
    started = true;
    for (int k = 0; k < ms; ++k) {
      throwIfCancelled(&cancel);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return [value, &out] { out = value; };
  };
}

void waitStarted(const std::atomic<bool>& started) {
  for (int k = 0; k < 5000 && !started; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  REQUIRE(started);
}

}  // namespace

TEST_CASE("view jobs: a job runs on the worker, its GL step is handed over once") {
  ViewJobRunner jobs;
  CHECK(!jobs.busy());
  CHECK(!jobs.takeFinished());
  std::thread::id ran;
  jobs.submit([&](const CancelToken&) -> ViewJobRunner::Apply {
    ran = std::this_thread::get_id();
    return [] {};
  });
  REQUIRE(jobs.waitIdle(10));
  CHECK(ran != std::this_thread::get_id());
  CHECK(jobs.busy());  // its step waits to be taken
  CHECK(static_cast<bool>(jobs.takeFinished()));
  CHECK(!jobs.takeFinished());
  CHECK(!jobs.busy());
}

TEST_CASE("view jobs: a newer job cancels the running one within 200 ms, and only its result arrives") {
  ViewJobRunner jobs;
  int out = 0;
  std::atomic<bool> firstStarted = false, secondStarted = false;
  jobs.submit(polling(10000, 1, out, firstStarted));
  waitStarted(firstStarted);
  const auto t0 = std::chrono::steady_clock::now();
  jobs.submit(polling(5, 2, out, secondStarted));
  waitStarted(secondStarted);
  CHECK(msSince(t0) < 200.0);  // the 10 s job stopped at its next poll
  REQUIRE(jobs.waitIdle(10));
  const ViewJobRunner::Apply apply = jobs.takeFinished();
  REQUIRE(apply);
  apply();
  CHECK(out == 2);
  CHECK(!jobs.takeFinished());
}

TEST_CASE("view jobs: a job let finish keeps its result; cancel() drops everything") {
  ViewJobRunner jobs;
  int out = 0;
  std::atomic<bool> firstStarted = false, secondStarted = false;
  jobs.submit(polling(100, 1, out, firstStarted));
  waitStarted(firstStarted);
  jobs.submit(polling(5000, 2, out, secondStarted), true);
  waitStarted(secondStarted);  // the first finished: its result waits
  ViewJobRunner::Apply apply = jobs.takeFinished();
  REQUIRE(apply);
  apply();
  CHECK(out == 1);
  jobs.cancel();
  REQUIRE(jobs.waitIdle(10));
  CHECK(!jobs.takeFinished());
  CHECK(!jobs.busy());
}

TEST_CASE("view jobs: an error of a job is thrown by its GL step") {
  ViewJobRunner jobs;
  jobs.submit([](const CancelToken&) -> ViewJobRunner::Apply { throw InputError("bake failed: no field"); });
  REQUIRE(jobs.waitIdle(10));
  const ViewJobRunner::Apply apply = jobs.takeFinished();
  REQUIRE(apply);
  CHECK_THROWS_WITH_AS(apply(), "bake failed: no field", InputError);
}
