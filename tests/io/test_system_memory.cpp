#include <doctest/doctest.h>

#include "io/system_memory.h"

using namespace hermite;

TEST_CASE("system memory: MemAvailable and the cgroup v2 path are parsed; the live reading is bounded") {
  const char* meminfo = "MemTotal:       24576000 kB\nMemFree:        15000000 kB\nMemAvailable:   18874368 kB\n";
  REQUIRE(meminfoAvailableBytes(meminfo).has_value());
  CHECK(*meminfoAvailableBytes(meminfo) == 18874368ull * 1024);
  CHECK_FALSE(meminfoAvailableBytes("MemTotal: 1 kB\n").has_value());
  CHECK(cgroupV2Path("4:memory:/a\n0::/user.slice/x.scope\n").value() == "/user.slice/x.scope");
  CHECK_FALSE(cgroupV2Path("4:memory:/a\n").has_value());
  // This machine: some limit applies (MemAvailable at least), and it is below 2⁶³ bytes.
  const AvailableMemory live = querySystemMemory();
  CHECK(live.bytes < (1ull << 63));
  CHECK_FALSE(live.limitedBy.empty());
}
