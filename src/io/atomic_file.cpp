#include "io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "core/base/errors.h"
#include "io/temporary_file_registry.h"

namespace hermite {

namespace {

constexpr std::size_t kBufferBytes = 1 << 20;

std::string randomSuffix(std::mt19937_64& rng) {
  static constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::uniform_int_distribution<int> pick(0, static_cast<int>(sizeof(kChars)) - 2);
  std::string s(6, 'x');
  for (char& c : s) c = kChars[pick(rng)];
  return s;
}

// The file a write to `path` lands in: `path` itself, or the end of its chain of symbolic links
// (relative links resolve against the link's folder), so that the link stays a link.
// EnvironmentError on a loop or a chain longer than 40 links.
std::string resolveLinks(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::error_code ec;
  for (int hop = 0; hop < 40; ++hop) {
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p.string();
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) throw EnvironmentError(path + ": cannot write (reading the symbolic link failed: " + ec.message() + ")");
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  throw EnvironmentError(path + ": cannot write (too many levels of symbolic links)");
}

// Syncs the folder holding `path` so that the rename itself survives a crash. Folders that do
// not support fsync (some network and virtual file systems) are left as they are.
void syncParentFolder(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const int fd = ::open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)), target_(resolveLinks(path_)) {
  std::random_device device;
  std::mt19937_64 rng((static_cast<std::uint64_t>(device()) << 32) ^ device() ^
                      static_cast<std::uint64_t>(::getpid()));
  int error = 0;
  // O_EXCL with fresh names: never follows or reuses somebody else's file. Mode 0666 is
  // reduced by the umask like any newly created file.
  for (int attempt = 0; attempt < 100; ++attempt) {
    tempPath_ = target_ + ".tmp-" + randomSuffix(rng);
    fd_ = ::open(tempPath_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ >= 0) break;
    error = errno;
    if (error != EEXIST) break;
  }
  if (fd_ < 0) {
    tempPath_.clear();
    throw EnvironmentError(path_ + ": cannot write (creating a temporary file in its directory failed: " +
                           std::strerror(error) + ")");
  }
  registerTemporaryFile(tempPath_);
  // An existing file keeps its permission bits (a 0600 file stays 0600).
  struct stat existing {};
  if (::stat(target_.c_str(), &existing) == 0 && S_ISREG(existing.st_mode))
    ::fchmod(fd_, existing.st_mode & 07777);
  buffer_.reserve(kBufferBytes);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !tempPath_.empty()) ::unlink(tempPath_.c_str());
  if (!tempPath_.empty()) unregisterTemporaryFile(tempPath_);
}

void AtomicFileWriter::fail(const std::string& what, int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tempPath_.empty()) {
    ::unlink(tempPath_.c_str());
    unregisterTemporaryFile(tempPath_);
  }
  tempPath_.clear();
  throw EnvironmentError(path_ + ": cannot write (" + what + ": " + std::strerror(error) +
                         "); the previous file, if any, is unchanged");
}

void AtomicFileWriter::write(std::string_view bytes) {
  if (fd_ < 0) throw EnvironmentError(path_ + ": write after the file was closed");
  buffer_.append(bytes);
  if (buffer_.size() >= kBufferBytes) flushBuffer();
}

void AtomicFileWriter::flushBuffer() {
  const char* p = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write failed", errno);
    }
    if (n == 0) fail("write made no progress", EIO);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

void AtomicFileWriter::commit() {
  if (fd_ < 0) throw EnvironmentError(path_ + ": commit after the file was closed");
  flushBuffer();
  if (::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) fail("fsync failed", errno);
  const int fd = fd_;
  fd_ = -1;  // closed below whatever close() returns
  if (::close(fd) != 0) fail("close failed", errno);
  if (std::rename(tempPath_.c_str(), target_.c_str()) != 0) fail("rename failed", errno);
  committed_ = true;
  unregisterTemporaryFile(tempPath_);
  syncParentFolder(target_);
}

void writeFileAtomically(const std::string& path, std::string_view contents) {
  AtomicFileWriter writer(path);
  writer.write(contents);
  writer.commit();
}

}  // namespace hermite
