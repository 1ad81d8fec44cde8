#pragma once
// A name table for an enum: the one place where an enum's values are spelled (in scene files,
// on the command line, in messages). The name function, the parser and its list of valid
// choices all read the same table.

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace hermite {

template <class E>
struct EnumName {
  std::string_view name;
  E value;
};

// The table's name for `value` (the first entry's when the value is missing from the table).
template <class E>
constexpr std::string_view nameIn(std::span<const EnumName<E>> table, E value) {
  for (const EnumName<E>& entry : table)
    if (entry.value == value) return entry.name;
  return table.front().name;
}

// The value named `name`, if the table has it.
template <class E>
constexpr std::optional<E> valueIn(std::span<const EnumName<E>> table, std::string_view name) {
  for (const EnumName<E>& entry : table)
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

// "a, b, c": the names in table order, for messages.
template <class E>
std::string namesIn(std::span<const EnumName<E>> table) {
  std::string out;
  for (const EnumName<E>& entry : table) out += (out.empty() ? "" : ", ") + std::string(entry.name);
  return out;
}

}  // namespace hermite
