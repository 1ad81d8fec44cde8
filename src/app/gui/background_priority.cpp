#include "app/gui/background_priority.h"

#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>

// OpenBLAS's pthread_create-like entry (driver/others/blas_server.c): runs function(args + k·stride)
// for k < numthreads, the first on the caller and the others on the pool's threads. Weak: the
// OpenMP build of OpenBLAS does not export it.
extern "C" int gotoblas_pthread(int numthreads, void* function, void* args, int stride) __attribute__((weak));
// The pool's size plus the caller (OpenBLAS's count at start-up, or the largest set since).
extern "C" int blas_num_threads __attribute__((weak));

namespace hermite::app {

namespace {

struct PoolCall {
  int nice = 0;
  bool idle = false;  // SCHED_IDLE instead of the nice value
  std::mutex mutex;
  std::vector<pid_t> reached;
};

void lowerOnPoolThread(void* arg) {
  auto* call = static_cast<PoolCall*>(arg);
  if (call->idle)
    idleCallingThread();
  else
    lowerCallingThreadPriority(call->nice);
  std::lock_guard lock(call->mutex);
  const pid_t tid = currentThreadId();
  if (std::find(call->reached.begin(), call->reached.end(), tid) == call->reached.end()) call->reached.push_back(tid);
}

// An integer environment variable within [lo, hi], else `fallback`.
int envInt(const char* name, int lo, int hi, int fallback) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == 0) return fallback;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  return *end == 0 && v >= lo && v <= hi ? int(v) : fallback;
}

}  // namespace

bool idleSchedFromEnv(const char* value, bool unset) {
  if (value != nullptr && std::strcmp(value, "idle") == 0) return true;
  if (value != nullptr && std::strcmp(value, "normal") == 0) return false;
  return unset;
}

FitPriority windowFitPriority() {
  FitPriority p;
  p.nice = envInt("HERMITE_FIT_NICE", 0, 19, kFitNice);
  p.threads = envInt("HERMITE_FIT_THREADS", 0, 1024, 0);
  p.idle = idleSchedFromEnv(std::getenv("HERMITE_FIT_SCHED"), kFitIdle);
  return p;
}

bool idleCallingThread() {
  sched_param param{};
  param.sched_priority = 0;
  return sched_setscheduler(currentThreadId(), SCHED_IDLE, &param) == 0;
}

bool threadIsIdle(pid_t tid) { return sched_getscheduler(tid) == SCHED_IDLE; }

int viewWorkerNice() {
  static const int nice = envInt("HERMITE_VIEW_NICE", 0, 19, kViewWorkerNice);
  return nice;
}

bool viewWorkerIdle() {
  static const bool idle = idleSchedFromEnv(std::getenv("HERMITE_VIEW_SCHED"), kViewWorkerIdle);
  return idle;
}

void lowerViewWorkerPriority() {
  lowerCallingThreadPriority(viewWorkerNice());
  if (viewWorkerIdle()) idleCallingThread();
}

pid_t currentThreadId() { return static_cast<pid_t>(syscall(SYS_gettid)); }

int threadNice(pid_t tid) {
  errno = 0;
  const int n = getpriority(PRIO_PROCESS, static_cast<id_t>(tid));
  return errno == 0 ? n : 0;
}

int lowerCallingThreadPriority(int nice) {
  const pid_t tid = currentThreadId();
  const int now = threadNice(tid);
  const int wanted = std::clamp(nice, 0, 19);
  if (wanted > now) setpriority(PRIO_PROCESS, static_cast<id_t>(tid), wanted);
  return threadNice(tid);
}

namespace {

// Runs lowerOnPoolThread on the caller and on every thread of OpenBLAS's pool.
std::vector<pid_t> onBlasPool(PoolCall& call) {
  // Without a pool (one thread) OpenBLAS would hand the second call to a thread that does not
  // exist and wait for it forever.
  if (gotoblas_pthread == nullptr || &blas_num_threads == nullptr || blas_num_threads < 2) return {};
  // One call for the caller and one per pool thread; stride 0: every call gets the same argument.
  gotoblas_pthread(blas_num_threads, reinterpret_cast<void*>(&lowerOnPoolThread), &call, 0);
  return call.reached;
}

}  // namespace

std::vector<pid_t> lowerBlasPoolPriority(int nice) {
  PoolCall call;
  call.nice = nice;
  return onBlasPool(call);
}

std::vector<pid_t> idleBlasPool() {
  PoolCall call;
  call.idle = true;
  return onBlasPool(call);
}

}  // namespace hermite::app
