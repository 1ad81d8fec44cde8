#pragma once
// A read-mostly map from 64-bit cell keys to [begin, end) ranges, by open addressing with linear
// probing in one array (a power of two, at most half full). The spacing search looks up 27 or
// more cells per sample; std::unordered_map's node chasing made those lookups 2.9 % of the
// elephant's `mesh` (docs/performance.md, "Serial stretches of mesh"). Keys must differ from
// kEmpty (the spacing grid's keys use 63 bits).

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace hermite {

class FlatCellMap {
 public:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  struct Slot {
    std::uint64_t key = kEmpty;
    std::int64_t begin = 0, end = 0;
  };

  // Room for `count` keys.
  explicit FlatCellMap(std::size_t count = 0) {
    std::size_t size = 16;
    int bits = 4;
    while (size < 2 * count) size *= 2, ++bits;
    slots_.assign(size, Slot{});
    mask_ = size - 1;
    shift_ = 64 - bits;
  }

  // Adds key → [begin, end); the key must not be present yet.
  void insert(std::uint64_t key, std::int64_t begin, std::int64_t end) {
    std::size_t i = home(key);
    while (slots_[i].key != kEmpty) i = (i + 1) & mask_;
    slots_[i] = Slot{key, begin, end};
  }

  // The slot of `key`, or null.
  const Slot* find(std::uint64_t key) const {
    for (std::size_t i = home(key);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.key == key) return &s;
      if (s.key == kEmpty) return nullptr;
    }
  }

 private:
  // Fibonacci hashing: the top bits of key·2⁶⁴/φ, which mixes the packed cell coordinates.
  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 60;
};

}  // namespace hermite
