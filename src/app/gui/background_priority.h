#pragma once
// CPU priority of the window's background work (docs/design.md, Threads): a fit's threads run at
// a higher nice value than the GUI thread and llvmpipe's rasteriser threads, so that the kernel's
// fair scheduler gives the frame the cores whenever it wants them and the fit all of them
// otherwise (issue 18: frames ≤ 33 ms while a dense fit runs on 2 cores).
//
// Linux keeps a nice value per thread: setpriority(PRIO_PROCESS, tid, n) changes one thread,
// and a thread starts with its creator's value. Raising it needs no privilege; lowering it again
// does, so a thread lowered here stays lowered for its lifetime.

#include <sys/types.h>

#include <vector>

namespace hermite::app {

// The calling thread's nice value becomes at least `nice` (0..19); threads it creates later (its
// OpenMP team) start with it. Returns the value now in effect.
int lowerCallingThreadPriority(int nice);

// The same for every thread of OpenBLAS's own pool (its pthread build, which creates the pool at
// start-up from the main thread): a call through OpenBLAS's gotoblas_pthread runs the change on
// each pool thread and on the caller, which is lowered too. Returns the distinct thread ids it
// reached, the caller included; empty when OpenBLAS has no such pool (its OpenMP build runs on
// the caller's OpenMP team instead, which lowerCallingThreadPriority covers when it comes first).
// A fork() shuts OpenBLAS's pool down (its pthread_atfork handler) and the next BLAS call starts
// a new one from the calling thread, with that thread's nice value.
std::vector<pid_t> lowerBlasPoolPriority(int nice);

// The calling thread moves to the SCHED_IDLE policy (sched(7)): it runs only on a core no
// normal thread wants, and a waking normal thread (the GUI thread, llvmpipe's rasteriser threads)
// preempts it at once, whatever the nice values. Threads it creates later inherit the policy.
// Needs no privilege; leaving it again does (one-way, like the nice value). False when refused.
bool idleCallingThread();
// The same for every thread of OpenBLAS's pool and the caller (see lowerBlasPoolPriority).
std::vector<pid_t> idleBlasPool();
// The calling thread or `tid` runs under SCHED_IDLE (tests).
bool threadIsIdle(pid_t tid);

// What the window's fits run at (FitWorker::setBackgroundPriority): nice kFitNice and every core,
// unless the environment says otherwise (docs/cli.md, Environment): HERMITE_FIT_NICE (0..19),
// HERMITE_FIT_THREADS (≥ 1; 0 or unset: the process's count) and HERMITE_FIT_SCHED ("idle":
// SCHED_IDLE besides the nice value; "normal": the nice value alone; unset: kFitIdle).
struct FitPriority {
  int nice = 0;
  int threads = 0;
  bool idle = false;
};
inline constexpr bool kFitIdle = false;
inline constexpr int kFitNice = 10;
FitPriority windowFitPriority();
// A HERMITE_*_SCHED value: "idle" true, "normal" false, anything else (or none) `unset`.
bool idleSchedFromEnv(const char* value, bool unset);

// The nice value of the view worker's jobs (bakes, exact refinement; scene_view.h), which lower
// their own thread before they start, so that its OpenMP team inherits it: kViewWorkerNice
// unless HERMITE_VIEW_NICE (0..19) says otherwise. The worker and its team end with their
// renderer, so nothing else in the process is affected.
inline constexpr int kViewWorkerNice = 10;
int viewWorkerNice();
// Whether the view worker's jobs also move to SCHED_IDLE: HERMITE_VIEW_SCHED ("idle" / "normal";
// unset: kViewWorkerIdle). A core that runs only SCHED_IDLE work counts as idle when a thread
// wakes, so llvmpipe's rasteriser threads land on it at once instead of sharing the GUI's core.
inline constexpr bool kViewWorkerIdle = false;
bool viewWorkerIdle();
// What a view job does first: viewWorkerNice(), then SCHED_IDLE when viewWorkerIdle().
void lowerViewWorkerPriority();

// The nice value of thread `tid` of this process (getpriority), for tests and logs.
int threadNice(pid_t tid);

// The calling thread's id (gettid).
pid_t currentThreadId();

}  // namespace hermite::app
