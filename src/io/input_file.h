#pragma once
// The one way every input file is read (scene JSON, point and probe files, meshes, glTF
// buffers): regular files only, never blocking on a FIFO, and never more than a size cap
// (default 4 GiB; `--max-input-size` changes it, docs/cli.md). A device such as /dev/zero, a
// FIFO, a socket or a directory is refused by name before anything is read.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace hermite {

constexpr std::uint64_t kDefaultMaxInputSize = std::uint64_t{4} << 30;  // bytes

// The cap readInputFile applies, in bytes (≥ 1); process-wide, set once by the command line.
std::uint64_t maxInputSize();
void setMaxInputSize(std::uint64_t bytes);

// The whole file. InputError "PATH: cannot open (REASON)" when it is missing or a directory,
// "PATH: cannot read (it is a FIFO, not a regular file)" for special files, and a message with
// the size, the cap and the remedy when it is larger than maxInputSize(). `what` names the
// content in that message ("scene", "point file", "PLY"). An empty file is returned as "".
std::string readInputFile(const std::string& path, std::string_view what);

// At most the first `bytes` bytes of the file, with readInputFile's checks and errors but no
// size cap (the read is bounded): for sniffing a file's layout before it is loaded.
std::string readInputFileHead(const std::string& path, std::size_t bytes);

// "a FIFO", "a character device", … for a stat mode that is not a regular file.
std::string fileKindName(unsigned mode);

}  // namespace hermite
