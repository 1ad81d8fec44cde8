#pragma once
// Crash- and failure-safe file replacement: the bytes go to a temporary "<path>.tmp-XXXXXX" in
// the same directory, which is flushed, synced and closed before std::rename moves it over
// `path`; the directory is then synced so the rename is durable. Any failure removes the
// temporary and leaves an existing `path` untouched; so does SIGINT or SIGTERM
// (temporary_file_registry.h). An existing file keeps its permission bits. When `path` is a
// symbolic link, the link stays and the file it points to is replaced (the temporary sits next
// to that file).

#include <string>
#include <string_view>

namespace hermite {

class AtomicFileWriter {
 public:
  // Creates the temporary; EnvironmentError when the directory is missing or unwritable.
  explicit AtomicFileWriter(std::string path);
  // Removes the temporary unless commit() succeeded.
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  // Buffered; EnvironmentError on a failed write (disk full, file size limit, I/O error).
  void write(std::string_view bytes);
  // Flushes, syncs, closes and renames over the target; EnvironmentError on failure.
  void commit();

  const std::string& path() const { return path_; }
  const std::string& temporaryPath() const { return tempPath_; }

 private:
  void flushBuffer();
  [[noreturn]] void fail(const std::string& what, int error);

  std::string path_;
  std::string target_;  // path_ with its symbolic links resolved: the file that is replaced
  std::string tempPath_;
  std::string buffer_;
  int fd_ = -1;
  bool committed_ = false;
};

// One-shot form: writes `contents` to `path` through AtomicFileWriter.
void writeFileAtomically(const std::string& path, std::string_view contents);

}  // namespace hermite
