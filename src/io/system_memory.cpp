#include "io/system_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <charconv>
#include <fstream>
#include <sstream>
#include <string>

namespace hermite {

namespace {

// The whole of a small kernel file (procfs and cgroupfs report size 0: read to the end).
std::optional<std::string> readSmallFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::optional<std::uint64_t> parseUnsigned(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end == text.data()) return std::nullopt;
  return v;
}

void lowerTo(AvailableMemory& out, std::uint64_t bytes, const char* limit) {
  if (bytes < out.bytes) out = AvailableMemory{bytes, limit};
}

// statm field `index` (0: size, 5: data), in bytes.
std::optional<std::uint64_t> statmBytes(int index) {
  const auto text = readSmallFile("/proc/self/statm");
  if (!text) return std::nullopt;
  std::istringstream in(*text);
  std::uint64_t pages = 0;
  for (int k = 0; k <= index; ++k)
    if (!(in >> pages)) return std::nullopt;
  return pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

void applyRlimit(AvailableMemory& out, int resource, int statmIndex, const char* name) {
  rlimit lim{};
  if (getrlimit(resource, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return;
  const std::uint64_t used = statmBytes(statmIndex).value_or(0);
  lowerTo(out, lim.rlim_cur > used ? lim.rlim_cur - used : 0, name);
}

// memory.max − memory.current of the cgroup at `path` and of every parent ("max": no limit).
void applyCgroup(AvailableMemory& out, std::string path) {
  for (;;) {
    const std::string dir = "/sys/fs/cgroup" + path;
    const auto max = readSmallFile(dir + "/memory.max");
    const auto current = readSmallFile(dir + "/memory.current");
    if (max && current && max->rfind("max", 0) != 0) {
      const auto m = parseUnsigned(*max), c = parseUnsigned(*current);
      if (m && c) lowerTo(out, *m > *c ? *m - *c : 0, "cgroup memory.max");
    }
    if (path.empty() || path == "/") return;
    path.erase(path.find_last_of('/'));
  }
}

// cgroup v1, as a container sees its own group at the mount point: limit_in_bytes −
// usage_in_bytes (no limit reads as a huge number, close to 2⁶³).
void applyCgroupV1(AvailableMemory& out) {
  const std::string dir = "/sys/fs/cgroup/memory/";
  const auto limit = readSmallFile(dir + "memory.limit_in_bytes");
  const auto usage = readSmallFile(dir + "memory.usage_in_bytes");
  if (!limit || !usage) return;
  const auto l = parseUnsigned(*limit), u = parseUnsigned(*usage);
  if (l && u && *l < (1ull << 60)) lowerTo(out, *l > *u ? *l - *u : 0, "cgroup memory.limit_in_bytes");
}

}  // namespace

std::optional<std::uint64_t> meminfoAvailableBytes(std::string_view meminfo) {
  const std::string_view key = "MemAvailable:";
  const std::size_t at = meminfo.find(key);
  if (at == std::string_view::npos) return std::nullopt;
  const auto kb = parseUnsigned(meminfo.substr(at + key.size()));
  if (!kb) return std::nullopt;
  return *kb * 1024;
}

std::optional<std::string_view> cgroupV2Path(std::string_view text) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    if (line.rfind("0::", 0) == 0) return line.substr(3);
    start = end + 1;
  }
  return std::nullopt;
}

AvailableMemory querySystemMemory() {
  AvailableMemory out;
  if (const auto meminfo = readSmallFile("/proc/meminfo"))
    if (const auto bytes = meminfoAvailableBytes(*meminfo)) lowerTo(out, *bytes, "MemAvailable");
  applyRlimit(out, RLIMIT_AS, 0, "RLIMIT_AS");
  applyRlimit(out, RLIMIT_DATA, 5, "RLIMIT_DATA");
  if (const auto cgroup = readSmallFile("/proc/self/cgroup"))
    if (const auto path = cgroupV2Path(*cgroup)) applyCgroup(out, std::string(*path));
  applyCgroupV1(out);
  return out;
}

}  // namespace hermite
