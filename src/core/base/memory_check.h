#pragma once
// Work sized before it starts: a large job states the memory it will hold at once (a
// PlannedAllocation) and checks it against what this process may still use (AvailableMemory)
// before allocating. A refusal is a MemoryLimitError (exit code 4) whose message carries the
// size needed, the size available, what limits it and the remedy.
//
// Core reads no operating-system files: the program installs the source of AvailableMemory at
// start-up (setAvailableMemorySource; the Linux reading is io/system_memory.h). Without one,
// memory counts as unlimited and every check passes.

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include "core/base/errors.h"

namespace hermite {

inline constexpr std::uint64_t kUnlimitedBytes = std::numeric_limits<std::uint64_t>::max();

// Memory a job will hold at its peak.
struct PlannedAllocation {
  std::uint64_t bytes = 0;  // peak bytes held at once (saturates at kUnlimitedBytes)
  std::string purpose;      // what needs it, e.g. "the dense fit of 20 844 unknowns (its system matrix)"
};

// Memory this process may still allocate: the smallest of the limits that apply.
struct AvailableMemory {
  std::uint64_t bytes = kUnlimitedBytes;
  std::string limitedBy;  // which limit is the smallest, e.g. "MemAvailable", "RLIMIT_AS", "cgroup memory.max"
};

// The job does not fit in the available memory. Exit code 4, like every environment limit.
class MemoryLimitError : public EnvironmentError {
 public:
  MemoryLimitError(const std::string& message, std::uint64_t needed, std::uint64_t available)
      : EnvironmentError(message), needed_(needed), available_(available) {}
  std::uint64_t needed() const { return needed_; }
  std::uint64_t available() const { return available_; }

 private:
  std::uint64_t needed_;
  std::uint64_t available_;
};

// Plans below this are not checked: querying the limits costs file reads, and a smaller job
// that still fails ends in the prompt out-of-memory exit.
inline constexpr std::uint64_t kUncheckedBytes = 32ull << 20;

// Throws MemoryLimitError when plan.bytes > available.bytes:
//   "PURPOSE needs 3.5 GB; this process has 1.2 GB available (MemAvailable); REMEDY"
void checkMemory(const PlannedAllocation& plan, std::string_view remedy, const AvailableMemory& available);
// The same against availableMemory(), for plans of at least kUncheckedBytes.
void checkMemory(const PlannedAllocation& plan, std::string_view remedy);

// What the installed source reports (unlimited without one). Safe to call from any thread.
AvailableMemory availableMemory();
// Installs the source (null: unlimited). Tests install a fixed amount.
using AvailableMemorySource = AvailableMemory (*)();
void setAvailableMemorySource(AvailableMemorySource source);

// The product of the factors, saturating at kUnlimitedBytes instead of wrapping.
std::uint64_t saturatingProduct(std::initializer_list<std::uint64_t> factors);
// The sum, saturating likewise.
std::uint64_t saturatingSum(std::initializer_list<std::uint64_t> terms);

// Bytes for people: "512 B", "3.5 MB", "1.2 GB", "550 GB", "1.1 TB" (decimal units, 2–3 digits).
std::string formatBytes(std::uint64_t bytes);

}  // namespace hermite
