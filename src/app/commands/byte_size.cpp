#include "app/commands/byte_size.h"

#include <cctype>
#include <charconv>
#include <limits>
#include <string>

namespace hermite::app {

namespace {

// log2 of the multiplier a suffix stands for ("" 0, "K" 10, "MiB" 20, …); -1 when unknown.
int suffixShift(std::string_view suffix) {
  std::string s;
  for (char c : suffix) s += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (s.size() == 3 && s.substr(1) == "IB") s.resize(1);
  else if (s.size() == 2 && s[1] == 'B') s.resize(1);
  if (s.empty() || s == "B") return 0;
  if (s == "K") return 10;
  if (s == "M") return 20;
  if (s == "G") return 30;
  if (s == "T") return 40;
  return -1;
}

}  // namespace

std::optional<std::uint64_t> parseByteSize(std::string_view text) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [rest, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || rest == text.data()) return std::nullopt;
  const int shift = suffixShift(std::string_view(rest, static_cast<std::size_t>(end - rest)));
  if (shift < 0) return std::nullopt;
  if (shift > 0 && value > (std::numeric_limits<std::uint64_t>::max() >> shift)) return std::nullopt;
  return value << shift;
}

}  // namespace hermite::app
