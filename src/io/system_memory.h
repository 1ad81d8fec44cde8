#pragma once
// The memory this process may still allocate, read from Linux (the source that
// setAvailableMemorySource installs at start-up, core/base/memory_check.h): the smallest of
//   - MemAvailable of /proc/meminfo (what the kernel can give without swapping);
//   - RLIMIT_AS minus the address space in use (/proc/self/statm: size);
//   - RLIMIT_DATA minus the data segment in use (/proc/self/statm: data);
//   - memory.max minus memory.current of this process's cgroup (v2) and of each parent;
//   - cgroup v1: memory.limit_in_bytes minus memory.usage_in_bytes of /sys/fs/cgroup/memory.
// A limit that cannot be read does not count.

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/base/memory_check.h"

namespace hermite {

AvailableMemory querySystemMemory();

// The parts, for tests: "MemAvailable:  123 kB" of a meminfo text, in bytes.
std::optional<std::uint64_t> meminfoAvailableBytes(std::string_view meminfo);
// The v2 path of /proc/self/cgroup ("0::/user.slice/x.scope" → "/user.slice/x.scope").
std::optional<std::string_view> cgroupV2Path(std::string_view procSelfCgroup);

}  // namespace hermite
