#include "core/base/memory_check.h"

#include <atomic>
#include <cstdio>

namespace hermite {

namespace {

std::atomic<AvailableMemorySource> gSource{nullptr};

}  // namespace

void checkMemory(const PlannedAllocation& plan, std::string_view remedy, const AvailableMemory& available) {
  if (plan.bytes <= available.bytes) return;
  std::string message = plan.purpose + " needs " + formatBytes(plan.bytes) + "; this process has " +
                        formatBytes(available.bytes) + " available";
  if (!available.limitedBy.empty()) message += " (" + available.limitedBy + ")";
  if (!remedy.empty()) message += "; " + std::string(remedy);
  throw MemoryLimitError(message, plan.bytes, available.bytes);
}

void checkMemory(const PlannedAllocation& plan, std::string_view remedy) {
  if (plan.bytes < kUncheckedBytes) return;
  checkMemory(plan, remedy, availableMemory());
}

AvailableMemory availableMemory() {
  const AvailableMemorySource source = gSource.load();
  return source ? source() : AvailableMemory{};
}

void setAvailableMemorySource(AvailableMemorySource source) { gSource.store(source); }

std::uint64_t saturatingProduct(std::initializer_list<std::uint64_t> factors) {
  std::uint64_t p = 1;
  for (std::uint64_t f : factors) {
    if (f == 0) return 0;
    p = p > kUnlimitedBytes / f ? kUnlimitedBytes : p * f;
  }
  return p;
}

std::uint64_t saturatingSum(std::initializer_list<std::uint64_t> terms) {
  std::uint64_t s = 0;
  for (std::uint64_t t : terms) s = s > kUnlimitedBytes - t ? kUnlimitedBytes : s + t;
  return s;
}

std::string formatBytes(std::uint64_t bytes) {
  if (bytes == kUnlimitedBytes) return "unlimited memory";
  static constexpr const char* kUnits[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  double v = static_cast<double>(bytes);
  int unit = 0;
  while (v >= 1000 && unit < 6) {
    v /= 1000;
    ++unit;
  }
  char buf[32];
  if (unit == 0) std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else std::snprintf(buf, sizeof buf, v < 10 ? "%.1f %s" : "%.0f %s", v, kUnits[unit]);
  return buf;
}

}  // namespace hermite
