#include <doctest/doctest.h>

#include <cstdint>

#include "app/commands/byte_size.h"

using hermite::app::parseByteSize;

TEST_CASE("byte_size: digits with an optional binary suffix") {
  CHECK(parseByteSize("4096") == std::uint64_t{4096});
  CHECK(parseByteSize("512M") == std::uint64_t{512} << 20);
  CHECK(parseByteSize("8G") == std::uint64_t{8} << 30);
  CHECK(parseByteSize("8g") == std::uint64_t{8} << 30);
  CHECK(parseByteSize("2GiB") == std::uint64_t{2} << 30);
  CHECK(parseByteSize("2gb") == std::uint64_t{2} << 30);
  CHECK(parseByteSize("3k") == std::uint64_t{3072});
  CHECK(parseByteSize("1T") == std::uint64_t{1} << 40);
  CHECK(parseByteSize("16777215T") == std::uint64_t{16777215} << 40);
  CHECK(parseByteSize("10B") == std::uint64_t{10});
  for (const char* bad : {"", "G", "-1", "+1", "1.5G", "8X", "8 G", " 8", "8GG", "16777216T", "99999999999999999999"}) {
    CAPTURE(bad);
    CHECK(!parseByteSize(bad).has_value());
  }
}
