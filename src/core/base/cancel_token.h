#pragma once
// Cooperative cancellation of long work (fits, factorisations, PU boxes, bakes, meshing). The
// owner keeps the token; the work polls cancelled() between blocks of at most ~50 ms and throws
// Cancelled, so that the cores are free within 200 ms of cancel().

#include <atomic>
#include <stdexcept>

namespace hermite {

class CancelToken {
 public:
  void cancel() { flag_.store(true, std::memory_order_relaxed); }
  void reset() { flag_.store(false, std::memory_order_relaxed); }
  bool cancelled() const { return flag_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> flag_{false};
};

// Thrown by work that saw its token set. Not an error: the caller asked for it.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

// Throws Cancelled when `token` is set (a null token never is).
inline void throwIfCancelled(const CancelToken* token) {
  if (token && token->cancelled()) throw Cancelled();
}

}  // namespace hermite
