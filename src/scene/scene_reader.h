#pragma once
// Reading the values of one scene document (docs/scene-format.md): each reader checks a JSON value's
// type and range and throws InputError "<source>: <key.path>: <what was expected> (got ...)".
// The key tables (scene_keys.h) say which keys an object holds; this class reads one value.

#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/base/errors.h"
#include "core/base/enum_names.h"

namespace hermite {

// A short description of a JSON value for "(got ...)" in messages.
std::string describeJson(const nlohmann::json& v);
// "parent.key" ("key" at the top level) and "parent[i]".
std::string childPath(const std::string& parent, std::string_view key);
std::string indexPath(const std::string& parent, std::size_t i);

class SceneReader {
 public:
  using json = nlohmann::json;

  SceneReader(std::string source, std::string baseDirectory)
      : source_(std::move(source)), baseDirectory_(std::move(baseDirectory)) {}

  const std::string& source() const { return source_; }
  // `file` as written in the scene, resolved against the scene file's folder.
  std::string resolvePath(const std::string& file) const;

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(source_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }

  // Checks that `v` is an object whose keys are all in `keys` (suggesting a near miss).
  void object(const json& v, const std::string& path, std::span<const std::string_view> keys) const;
  static const json* find(const json& object, std::string_view key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  double number(const json& v, const std::string& path) const;
  double positive(const json& v, const std::string& path) const;
  double nonNegative(const json& v, const std::string& path) const;
  int integer(const json& v, const std::string& path, int lo, int hi) const;
  bool boolean(const json& v, const std::string& path) const;
  std::string string(const json& v, const std::string& path) const;
  std::vector<double> numbers(const json& v, const std::string& path, std::size_t n, std::string_view shape) const;
  template <std::size_t N>
  std::array<double, N> fixed(const json& v, const std::string& path, std::string_view shape) const {
    const std::vector<double> values = numbers(v, path, N, shape);
    std::array<double, N> out{};
    std::copy(values.begin(), values.end(), out.begin());
    return out;
  }
  // Vectors of the scene's dimension: [[x, y(, z)], ...].
  std::vector<std::vector<double>> vectors(const json& v, const std::string& path, int dim) const;

  // One of the table's names.
  template <class E>
  E choice(const json& v, const std::string& path, std::span<const EnumName<E>> table) const {
    const std::string name = string(v, path);
    if (const auto value = valueIn(table, name)) return *value;
    fail(path, "must be one of: " + namesIn(table) + " (got " + describeJson(v) + ")");
  }
  // Calls a parser from another module (kernel, polynomial, solver) and prefixes its message.
  template <class Parse>
  auto named(const json& v, const std::string& path, Parse parse) const {
    const std::string name = string(v, path);
    try {
      return parse(std::string_view(name));
    } catch (const InputError& e) {
      fail(path, e.what());
    }
  }
  // A name from a list of (name, description) pairs, e.g. the presets.
  std::string listed(const json& v, const std::string& path,
                     const std::vector<std::pair<std::string, std::string>>& list) const;

 private:
  std::string source_;
  std::string baseDirectory_;
};

}  // namespace hermite
