#include "io/temporary_file_registry.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>

namespace hermite {

namespace {

constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;  // PATH_MAX on Linux, terminating zero included

struct Slot {
  std::atomic<bool> used{false};
  char path[kPathBytes] = {};
};

Slot g_slots[kSlots];
std::mutex g_registryMutex;  // registration and removal; the handler only reads

void removeTemporariesAndReraise(int signal) {
  for (Slot& slot : g_slots)
    if (slot.used.load(std::memory_order_acquire)) ::unlink(slot.path);
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

// Installs the handler for each signal still at its default action (checked at every
// registration: a program may reset a signal to its default at any time).
void installHandlers() {
  for (const int signal : {SIGINT, SIGTERM}) {
    struct sigaction current {};
    if (::sigaction(signal, nullptr, &current) != 0) continue;
    if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;
    struct sigaction action {};
    action.sa_handler = removeTemporariesAndReraise;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal, &action, nullptr);
  }
}

}  // namespace

void registerTemporaryFile(const std::string& path) {
  if (path.size() >= kPathBytes) return;
  const std::lock_guard<std::mutex> lock(g_registryMutex);
  installHandlers();
  for (Slot& slot : g_slots) {
    if (slot.used.load(std::memory_order_relaxed)) continue;
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.used.store(true, std::memory_order_release);
    return;
  }
}

void unregisterTemporaryFile(const std::string& path) {
  const std::lock_guard<std::mutex> lock(g_registryMutex);
  for (Slot& slot : g_slots) {
    if (slot.used.load(std::memory_order_relaxed) && path == slot.path) {
      slot.used.store(false, std::memory_order_release);
      return;
    }
  }
}

}  // namespace hermite
