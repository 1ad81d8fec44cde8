#include "scene/scene_reader.h"

#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "core/base/edit_distance.h"
#include "core/base/format_number.h"
#include "io/quoted_token.h"

namespace hermite {

using json = nlohmann::json;

std::string describeJson(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::number_integer: return std::to_string(v.get<std::int64_t>());
    case json::value_t::number_unsigned: return std::to_string(v.get<std::uint64_t>());
    case json::value_t::number_float: return formatNumber(v.get<double>());
    case json::value_t::string: {
      std::string s = v.dump();
      if (s.size() > 60) s = s.substr(0, 57) + "...\"";
      return "string " + s;
    }
    case json::value_t::array: return "an array of " + std::to_string(v.size()) + " elements";
    case json::value_t::object: return "an object";
    default: return "an unsupported value";
  }
}

std::string childPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string indexPath(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

namespace {

std::string joinNames(std::span<const std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

}  // namespace

std::string SceneReader::resolvePath(const std::string& file) const {
  const std::filesystem::path p(file);
  return p.is_absolute() || baseDirectory_.empty() ? file : (std::filesystem::path(baseDirectory_) / p).string();
}

void SceneReader::object(const json& v, const std::string& path, std::span<const std::string_view> keys) const {
  if (!v.is_object()) {
    if (path.empty()) fail("", "the scene must be a JSON object (got " + describeJson(v) + ")");
    fail(path, "must be an object (got " + describeJson(v) + ")");
  }
  for (const auto& item : v.items()) {
    const std::string& key = item.key();
    if (std::find(keys.begin(), keys.end(), std::string_view(key)) != keys.end()) continue;
    std::string what = "unknown key (expected one of: " + joinNames(keys) + ")";
    std::string_view best;
    std::size_t bestDistance = 3;
    for (std::string_view k : keys) {
      // A key much longer than every known one is no typo (and its distance would be slow).
      const std::size_t d = key.size() > k.size() + bestDistance ? bestDistance : editDistance(key, k);
      if (d < bestDistance) bestDistance = d, best = k;
    }
    if (!best.empty()) what += "; did you mean '" + std::string(best) + "'?";
    fail(childPath(path, shortenedToken(key)), what);
  }
}

double SceneReader::number(const json& v, const std::string& path) const {
  if (!v.is_number()) fail(path, "must be a number (got " + describeJson(v) + ")");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path, "must be a finite number (got " + describeJson(v) + ")");
  return d;
}

double SceneReader::positive(const json& v, const std::string& path) const {
  const double d = number(v, path);
  if (!(d > 0)) fail(path, "must be > 0 (got " + describeJson(v) + ")");
  return d;
}

double SceneReader::nonNegative(const json& v, const std::string& path) const {
  const double d = number(v, path);
  if (!(d >= 0)) fail(path, "must be >= 0 (got " + describeJson(v) + ")");
  return d;
}

int SceneReader::integer(const json& v, const std::string& path, int lo, int hi) const {
  auto range = [&] {
    if (lo == INT_MIN && hi == INT_MAX) return "must be an integer in the 32-bit range (got " + describeJson(v) + ")";
    if (hi == INT_MAX) return "must be >= " + std::to_string(lo) + " (got " + describeJson(v) + ")";
    return "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " + describeJson(v) + ")";
  };
  long long value = 0;
  if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi)) fail(path, range());
    value = static_cast<long long>(u);
  } else if (v.is_number_integer()) {
    value = v.get<std::int64_t>();
  } else if (v.is_number_float()) {
    const double d = v.get<double>();
    if (!std::isfinite(d) || d != std::floor(d)) fail(path, "must be an integer (got " + describeJson(v) + ")");
    if (d < lo || d > hi) fail(path, range());
    value = static_cast<long long>(d);
  } else {
    fail(path, "must be an integer (got " + describeJson(v) + ")");
  }
  if (value < lo || value > hi) fail(path, range());
  return static_cast<int>(value);
}

bool SceneReader::boolean(const json& v, const std::string& path) const {
  if (!v.is_boolean()) fail(path, "must be true or false (got " + describeJson(v) + ")");
  return v.get<bool>();
}

std::string SceneReader::string(const json& v, const std::string& path) const {
  if (!v.is_string()) fail(path, "must be a string (got " + describeJson(v) + ")");
  return v.get<std::string>();
}

std::vector<double> SceneReader::numbers(const json& v, const std::string& path, std::size_t n,
                                         std::string_view shape) const {
  if (!v.is_array() || v.size() != n)
    fail(path, "must be an array of " + std::to_string(n) + " numbers " + std::string(shape) + " (got " +
                   describeJson(v) + ")");
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = number(v[i], indexPath(path, i));
  return out;
}

std::vector<std::vector<double>> SceneReader::vectors(const json& v, const std::string& path, int dim) const {
  if (!v.is_array())
    fail(path, "must be an array of [" + std::string(dim == 2 ? "x, y" : "x, y, z") + "] entries (got " +
                   describeJson(v) + ")");
  const std::string shape = dim == 2 ? "(2D scene)" : "(3D scene)";
  std::vector<std::vector<double>> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out.push_back(numbers(v[i], indexPath(path, i), static_cast<std::size_t>(dim), shape));
  return out;
}

std::string SceneReader::listed(const json& v, const std::string& path,
                                const std::vector<std::pair<std::string, std::string>>& list) const {
  const std::string name = string(v, path);
  std::string names;
  for (const auto& [n, description] : list) {
    if (n == name) return name;
    names += (names.empty() ? "" : ", ") + n;
  }
  fail(path, "unknown preset '" + name + "' (expected one of: " + names + ")");
}

}  // namespace hermite
