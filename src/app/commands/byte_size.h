#pragma once
// A byte count as written on the command line: digits with an optional binary suffix
// K, M, G or T (×1024, ×1024², …; also KiB, KB, k, … case-insensitively), e.g. 512M, 8G, 4096.

#include <cstdint>
#include <optional>
#include <string_view>

namespace hermite::app {

// The byte count, or nullopt when `text` is not of that form or exceeds 2^64 − 1.
std::optional<std::uint64_t> parseByteSize(std::string_view text);

}  // namespace hermite::app
