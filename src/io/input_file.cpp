#include "io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/base/errors.h"

namespace hermite {

namespace {

std::atomic<std::uint64_t> gMaxInputSize{kDefaultMaxInputSize};

// Closes the descriptor on every path out of readInputFile.
struct FileDescriptor {
  int fd = -1;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// "5000000000 bytes (4.66 GiB)": exact, and readable at a glance.
std::string formatBytes(std::uint64_t bytes) {
  char scaled[32] = "";
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  int unit = -1;
  while (value >= 1024 && unit < 5) value /= 1024, ++unit;
  if (unit >= 0) std::snprintf(scaled, sizeof(scaled), " (%.3g %s)", value, units[unit]);
  return std::to_string(bytes) + " bytes" + scaled;
}

void requireRegular(const std::string& path, const struct stat& st) {
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": cannot open (it is a directory)");
  if (!S_ISREG(st.st_mode))
    throw InputError(path + ": cannot read (it is " + fileKindName(st.st_mode) + ", not a regular file)");
}

[[noreturn]] void throwTooLarge(const std::string& path, std::string_view what, std::uint64_t size) {
  const std::uint64_t gib = std::uint64_t{1} << 30;
  const std::uint64_t enough = size / gib + 1;  // whole GiB above the size
  throw InputError(path + ": " + formatBytes(size) + " of " + std::string(what) +
                   " data, more than the input size limit of " + formatBytes(maxInputSize()) +
                   "; raise the limit with --max-input-size (e.g. --max-input-size " + std::to_string(enough) + "G)");
}

void requireWithinCap(const std::string& path, std::string_view what, std::uint64_t size) {
  if (size > maxInputSize()) throwTooLarge(path, what, size);
}

[[noreturn]] void throwReadError(const std::string& path) {
  throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
}

// Everything left in `fd`, expected to be `expected` bytes; a file that grows meanwhile is read
// on, up to the cap.
std::string readAll(int fd, std::size_t expected, const std::string& path, std::string_view what) {
  // One byte more than expected: the read that finds the end needs room, and growing the buffer
  // for it would copy the whole file once more.
  std::string bytes(expected + 1, '\0');
  std::size_t filled = 0;
  for (;;) {
    if (filled == bytes.size()) {
      const std::uint64_t cap = maxInputSize();
      // One byte past the cap says the file is too large; reading it into the buffer is safe.
      const std::uint64_t grown = std::min<std::uint64_t>(cap + 1, bytes.size() + (std::size_t{1} << 16));
      if (grown <= bytes.size()) throwTooLarge(path, what, bytes.size());
      bytes.resize(static_cast<std::size_t>(grown));
    }
    const ssize_t got = ::read(fd, bytes.data() + filled, bytes.size() - filled);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      throwReadError(path);
    }
    filled += static_cast<std::size_t>(got);
    if (filled > maxInputSize()) throwTooLarge(path, what, filled);
  }
  bytes.resize(filled);
  return bytes;
}

}  // namespace

std::uint64_t maxInputSize() { return gMaxInputSize.load(std::memory_order_relaxed); }

void setMaxInputSize(std::uint64_t bytes) { gMaxInputSize.store(bytes == 0 ? 1 : bytes, std::memory_order_relaxed); }

std::string fileKindName(unsigned mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISDIR(mode)) return "a directory";
  return "not a regular file";
}

namespace {

// Opens `path` for reading once it is known to be a regular file, by name and again on the
// descriptor (opening a FIFO for reading would block until a writer appears; O_NONBLOCK covers
// a file replaced by a FIFO between the two). `st` gets the open file's status.
void openRegular(const std::string& path, FileDescriptor& file, struct stat& st) {
  if (::stat(path.c_str(), &st) != 0) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  requireRegular(path, st);
  file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (file.fd < 0) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  if (::fstat(file.fd, &st) != 0) throwReadError(path);
  requireRegular(path, st);
}

}  // namespace

std::string readInputFile(const std::string& path, std::string_view what) {
  FileDescriptor file;
  struct stat st {};
  openRegular(path, file, st);
  requireWithinCap(path, what, static_cast<std::uint64_t>(st.st_size));
  return readAll(file.fd, static_cast<std::size_t>(st.st_size), path, what);
}

std::string readInputFileHead(const std::string& path, std::size_t bytes) {
  FileDescriptor file;
  struct stat st {};
  openRegular(path, file, st);
  std::string head(bytes, '\0');
  std::size_t filled = 0;
  while (filled < head.size()) {
    const ssize_t got = ::read(file.fd, head.data() + filled, head.size() - filled);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      throwReadError(path);
    }
    filled += static_cast<std::size_t>(got);
  }
  head.resize(filled);
  return head;
}

}  // namespace hermite
