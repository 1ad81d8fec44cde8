// The window's fits run below the GUI's CPU priority (issue 18: frames ≤ 33 ms while a dense fit
// runs): the fit's thread and OpenBLAS's pool threads get a higher nice value. The pool is
// process-wide and a lowered priority cannot be raised again without privileges, so the pool is
// checked in a child process.

#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <thread>

#include "app/gui/background_priority.h"
#include "core/base/threading.h"

using namespace hermite::app;

TEST_CASE("background priority: a thread lowers its own nice value, not its creator's") {
  const pid_t self = currentThreadId();
  const int before = threadNice(self);
  int inThread = -1, reported = -1;
  std::thread t([&] {
    reported = lowerCallingThreadPriority(std::min(before + 5, 19));
    inThread = threadNice(currentThreadId());
    // A value below the current one is not applied (it would need privileges to take back).
    lowerCallingThreadPriority(0);
    CHECK(threadNice(currentThreadId()) == inThread);
  });
  t.join();
  CHECK(reported == std::min(before + 5, 19));
  CHECK(inThread == reported);
  CHECK(threadNice(self) == before);
}

TEST_CASE("background priority: every OpenBLAS pool thread is lowered (child process)") {
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // 0: pass; 1: no thread reached besides the caller although OpenBLAS runs a pool; 2: a reached
    // thread (the caller runs the change too) kept a lower nice value.
    const std::vector<pid_t> reached = lowerBlasPoolPriority(15);
    int code = 0;
    if (hermite::blasThreadCount() > 1 && reached.size() < 2) code = 1;
    for (pid_t tid : reached)
      if (threadNice(tid) < 15) code = 2;
    _exit(code);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}

TEST_CASE("background priority: a thread moves itself to SCHED_IDLE, not its creator; its children inherit it") {
  const pid_t self = currentThreadId();
  REQUIRE(!threadIsIdle(self));
  bool moved = false, idle = false, childIdle = false;
  std::thread t([&] {
    moved = idleCallingThread();
    idle = threadIsIdle(currentThreadId());
    std::thread child([&] { childIdle = threadIsIdle(currentThreadId()); });
    child.join();
  });
  t.join();
  CHECK(moved);
  CHECK(idle);
  CHECK(childIdle);
  CHECK(!threadIsIdle(self));
}

TEST_CASE("background priority: every OpenBLAS pool thread moves to SCHED_IDLE (child process)") {
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // 0: pass; 1: no pool thread reached although OpenBLAS runs a pool; 2: a reached thread is not idle.
    const std::vector<pid_t> reached = idleBlasPool();
    int code = 0;
    if (hermite::blasThreadCount() > 1 && reached.size() < 2) code = 1;
    for (pid_t tid : reached)
      if (!threadIsIdle(tid)) code = 2;
    _exit(code);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}

TEST_CASE("background priority: HERMITE_*_SCHED values, and a view job's thread lowered as configured") {
  CHECK(idleSchedFromEnv("idle", false));
  CHECK(!idleSchedFromEnv("normal", true));
  CHECK(idleSchedFromEnv(nullptr, true));
  CHECK(!idleSchedFromEnv("IDLE", false));  // anything else keeps the default
  const pid_t self = currentThreadId();
  int nice = -1;
  bool idle = false;
  std::thread t([&] {
    lowerViewWorkerPriority();
    nice = threadNice(currentThreadId());
    idle = threadIsIdle(currentThreadId());
  });
  t.join();
  CHECK(nice >= viewWorkerNice());
  CHECK(idle == viewWorkerIdle());
  CHECK(!threadIsIdle(self));
}
