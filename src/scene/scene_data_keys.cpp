// The keys of `data` (docs/scene-format.md): exactly one source, a preset (with an optional count),
// a file, or inline points with one normal each.

#include <climits>

#include "scene/scene_file.h"
#include "scene/scene_keys.h"

namespace hermite {

namespace {

using json = nlohmann::json;
using Reader = SceneReader;

constexpr SceneKey<DataSpec> kDataKeys[] = {
    {"preset",
     [](const Reader& r, const json& x, const std::string& p, DataSpec& d, int) {
       d.preset = r.string(x, p);
       if (d.preset.empty()) r.fail(p, "must be a non-empty preset name");
     },
     [](const DataSpec& d, int) -> Written { return d.preset.empty() ? Written() : json(d.preset); }},
    {"count", [](const Reader& r, const json& x, const std::string& p, DataSpec& d, int) { d.count = r.integer(x, p, 0, INT_MAX); },
     [](const DataSpec& d, int) -> Written { return d.preset.empty() ? Written() : json(d.count); }},
    {"file",
     [](const Reader& r, const json& x, const std::string& p, DataSpec& d, int) {
       d.file = r.string(x, p);
       if (d.file.empty()) r.fail(p, "must be a non-empty path");
       d.resolvedFile = r.resolvePath(d.file);
     },
     [](const DataSpec& d, int) -> Written { return d.preset.empty() && !d.file.empty() ? json(d.file) : Written(); }},
    // "auto" (re-orient when inconsistent), true (always), false (never): io/point_file.h.
    {"orient_normals",
     [](const Reader& r, const json& x, const std::string& p, DataSpec& d, int) {
       if (x.is_boolean())
         d.orientNormals = x.get<bool>() ? GivenNormals::Always : GivenNormals::Never;
       else if (x.is_string() && x.get<std::string>() == "auto")
         d.orientNormals = GivenNormals::Auto;
       else
         r.fail(p, "must be \"auto\", true or false (got " + describeJson(x) + ")");
     },
     [](const DataSpec& d, int) -> Written {
       if (d.file.empty() || d.orientNormals == GivenNormals::Auto) return Written();
       return json(d.orientNormals == GivenNormals::Always);
     }},
    {"points", [](const Reader& r, const json& x, const std::string& p, DataSpec& d, int dim) { d.points = r.vectors(x, p, dim); },
     [](const DataSpec& d, int) -> Written { return d.isInline() ? json(d.points) : Written(); }},
    {"normals", [](const Reader& r, const json& x, const std::string& p, DataSpec& d, int dim) { d.normals = r.vectors(x, p, dim); },
     [](const DataSpec& d, int) -> Written { return d.isInline() ? json(d.normals) : Written(); }},
};

// Exactly one source, and the keys that go with it, before any value is read.
void checkSources(const Reader& r, const json& v) {
  const json* preset = Reader::find(v, "preset");
  const json* file = Reader::find(v, "file");
  const json* points = Reader::find(v, "points");
  const json* normals = Reader::find(v, "normals");
  std::vector<std::string> sources;
  if (preset) sources.push_back("data.preset");
  if (file) sources.push_back("data.file");
  if (points || normals) sources.push_back(points ? "data.points" : "data.normals");
  const std::string forms =
      "{\"preset\": NAME, \"count\": N}, {\"file\": PATH} or {\"points\": [...], \"normals\": [...]}";
  if (sources.empty()) r.fail("data", "no data source (expected one of " + forms + ")");
  if (sources.size() > 1) {
    std::string found;
    for (std::size_t i = 0; i < sources.size(); ++i)
      found += (i == 0 ? "" : i + 1 == sources.size() ? " and " : ", ") + sources[i];
    r.fail("data", "give exactly one data source, found " + found + " (expected one of " + forms + ")");
  }
  if (Reader::find(v, "count") && !preset) r.fail("data.count", "only allowed together with data.preset");
  if (Reader::find(v, "orient_normals") && !file)
    r.fail("data.orient_normals", "only allowed together with data.file (it says what happens to a file's normals)");
  if (preset || file) return;
  if (!points) r.fail("data.points", "missing: inline data needs both data.points and data.normals");
  if (!normals) r.fail("data.normals", "missing: inline data needs both data.points and data.normals");
}

}  // namespace

std::span<const SceneKey<DataSpec>> dataKeys() { return kDataKeys; }

DataSpec readDataSection(const SceneReader& reader, const json& v, int dim) {
  checkKeys<DataSpec>(reader, v, "data", kDataKeys);
  checkSources(reader, v);
  DataSpec data;
  readKeys<DataSpec>(reader, v, "data", kDataKeys, data, dim);
  if (data.points.size() != data.normals.size())
    reader.fail("data.normals", "has " + std::to_string(data.normals.size()) + " entries but data.points has " +
                                    std::to_string(data.points.size()) + " (one normal per point)");
  return data;
}

}  // namespace hermite
