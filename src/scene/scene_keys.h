#pragma once
// The scene format's keys, described once: each object of a scene document (fit, view, patch, …)
// is a table of SceneKey entries, and that table alone drives the reader's list of allowed keys,
// the order in which values are read and checked, and what the writer emits. A new key is one
// new entry (and a line in docs/scene-format.md).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene_reader.h"

namespace hermite {

// What a key writes: its JSON value, or nothing when the spec leaves the key out.
using Written = std::optional<nlohmann::json>;

template <class Spec>
struct SceneKey {
  using json = nlohmann::json;
  std::string_view name;
  // Reads the key's value (at `path`) into `spec`; `dim` is the scene's dimension.
  void (*read)(const SceneReader& reader, const json& value, const std::string& path, Spec& spec, int dim);
  // The key's value in a written document, or nothing for a key that this spec leaves out.
  Written (*write)(const Spec& spec, int dim);
  // When the key is absent: fails for a required key or sets a default that depends on others
  // (nullptr: the spec's own default stands).
  void (*absent)(const SceneReader& reader, const std::string& path, Spec& spec, int dim) = nullptr;
};

// Keys that are one member of the spec, read by one SceneReader check and written as they are:
// valueKey<Spec, &Spec::radius, &SceneReader::positive>("radius").
template <class Spec, auto Member, auto Check>
constexpr SceneKey<Spec> valueKey(std::string_view name) {
  return {name,
          [](const SceneReader& r, const nlohmann::json& x, const std::string& p, Spec& s, int) { s.*Member = (r.*Check)(x, p); },
          [](const Spec& s, int) -> Written { return nlohmann::json(s.*Member); }};
}

// An integer member in [Lo, Hi].
template <class Spec, auto Member, int Lo, int Hi>
constexpr SceneKey<Spec> integerKey(std::string_view name) {
  return {name,
          [](const SceneReader& r, const nlohmann::json& x, const std::string& p, Spec& s, int) { s.*Member = r.integer(x, p, Lo, Hi); },
          [](const Spec& s, int) -> Written { return nlohmann::json(s.*Member); }};
}

// An enum member spelled by its EnumName table.
template <class Spec, auto Member, const auto& Table>
constexpr SceneKey<Spec> enumKey(std::string_view name) {
  using E = std::remove_cvref_t<decltype(std::declval<Spec&>().*Member)>;
  return {name,
          [](const SceneReader& r, const nlohmann::json& x, const std::string& p, Spec& s, int) { s.*Member = r.choice<E>(x, p, Table); },
          [](const Spec& s, int) -> Written { return nlohmann::json(std::string(nameIn<E>(Table, s.*Member))); }};
}

// An enum member whose module parses and names it (kernel, polynomial, solver, blend).
template <class Spec, auto Member, auto Parse, auto Name>
constexpr SceneKey<Spec> namedKey(std::string_view name) {
  return {name,
          [](const SceneReader& r, const nlohmann::json& x, const std::string& p, Spec& s, int) { s.*Member = r.named(x, p, Parse); },
          [](const Spec& s, int) -> Written { return nlohmann::json(std::string(Name(s.*Member))); }};
}

template <class Spec>
std::vector<std::string_view> keyNames(std::span<const SceneKey<Spec>> keys) {
  std::vector<std::string_view> names;
  for (const SceneKey<Spec>& k : keys) names.push_back(k.name);
  return names;
}

// Checks that `v` is an object holding only the table's keys.
template <class Spec>
void checkKeys(const SceneReader& reader, const nlohmann::json& v, const std::string& path,
               std::span<const SceneKey<Spec>> keys) {
  reader.object(v, path, keyNames(keys));
}

// Reads the keys present in `v`, in table order (the order in which problems are reported).
template <class Spec>
void readKeys(const SceneReader& reader, const nlohmann::json& v, const std::string& path,
              std::span<const SceneKey<Spec>> keys, Spec& spec, int dim) {
  for (const SceneKey<Spec>& k : keys) {
    if (const nlohmann::json* x = SceneReader::find(v, k.name)) k.read(reader, *x, childPath(path, k.name), spec, dim);
    else if (k.absent) k.absent(reader, childPath(path, k.name), spec, dim);
  }
}

// checkKeys, then readKeys, into a default-constructed spec.
template <class Spec>
Spec readObject(const SceneReader& reader, const nlohmann::json& v, const std::string& path,
                std::span<const SceneKey<Spec>> keys, int dim) {
  checkKeys(reader, v, path, keys);
  Spec spec;
  readKeys(reader, v, path, keys, spec, dim);
  return spec;
}

template <class Spec>
nlohmann::json writeObject(const Spec& spec, std::span<const SceneKey<Spec>> keys, int dim) {
  nlohmann::json object = nlohmann::json::object();
  for (const SceneKey<Spec>& k : keys)
    if (Written value = k.write(spec, dim)) object[std::string(k.name)] = std::move(*value);
  return object;
}

// The sections of a scene document, each read and written through its key table.
struct DataSpec;
struct FitSpec;
struct TransformSpec;
struct ViewSpec;
struct PatchSpec;
struct HoleFillSpec;

std::span<const SceneKey<DataSpec>> dataKeys();
std::span<const SceneKey<FitSpec>> fitKeys();
std::span<const SceneKey<TransformSpec>> transformKeys();
std::span<const SceneKey<ViewSpec>> viewKeys();
std::span<const SceneKey<PatchSpec>> patchKeys();
std::span<const SceneKey<HoleFillSpec>> holeFillKeys();

DataSpec readDataSection(const SceneReader& reader, const nlohmann::json& v, int dim);
TransformSpec readTransformSection(const SceneReader& reader, const nlohmann::json& v, int dim);
// No transform: the identity, with a translation of the scene's dimension.
TransformSpec defaultTransform(int dim);

}  // namespace hermite
