#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <set>

#include "core/points/flat_cell_map.h"

TEST_CASE("FlatCellMap finds every inserted key and no other") {
  std::mt19937_64 rng(5);
  std::set<std::uint64_t> keys;
  // Packed cell keys (63 bits) with neighbouring cells, as the spacing grid makes them.
  while (keys.size() < 20000) keys.insert((rng() >> 1) & ~std::uint64_t(7));
  const std::set<std::uint64_t> base = keys;
  for (std::uint64_t k : base) keys.insert(k + 1);
  hermite::FlatCellMap map(keys.size());
  std::int64_t i = 0;
  for (std::uint64_t k : keys) map.insert(k, i, i + 3), ++i;
  i = 0;
  for (std::uint64_t k : keys) {
    const hermite::FlatCellMap::Slot* s = map.find(k);
    REQUIRE(s != nullptr);
    CHECK(s->begin == i);
    CHECK(s->end == i + 3);
    ++i;
  }
  int absentFound = 0;
  for (std::uint64_t k : base) absentFound += map.find(k + 2) != nullptr;
  CHECK(absentFound == 0);
  CHECK(hermite::FlatCellMap(0).find(42) == nullptr);
}
