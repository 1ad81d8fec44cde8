#include "scene/scene_file.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "core/base/errors.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/quoted_token.h"
#include "scene/data_file_scene.h"
#include "scene/scene_keys.h"

namespace hermite {

using json = nlohmann::json;

std::string_view sceneModeName(SceneMode m) { return nameIn<SceneMode>(kSceneModeNames, m); }
std::string_view fitMethodName(FitMethod m) { return nameIn<FitMethod>(kFitMethodNames, m); }
std::string_view projectionName(Projection p) { return nameIn<Projection>(kProjectionNames, p); }
std::string_view traceModeName(TraceMode t) { return nameIn<TraceMode>(kTraceModeNames, t); }
std::string_view transformMethodName(TransformMethod m) { return nameIn<TransformMethod>(kTransformMethodNames, m); }

bool TransformSpec::matrixIsIdentity() const {
  const std::size_t n = matrix.size() == 4 ? 2 : 3;
  for (std::size_t i = 0; i < matrix.size(); ++i)
    if (matrix[i] != (i / n == i % n ? 1.0 : 0.0)) return false;
  return true;
}

bool TransformSpec::isIdentity() const {
  const bool noTranslation =
      std::all_of(translate.begin(), translate.end(), [](double v) { return v == 0.0; });
  // A whole number of turns is the identity rotation exactly, whatever the axis.
  const bool noRotation3d = std::fmod(rotateAxisAngleDeg[3], 360.0) == 0.0;
  const bool noRotation2d = std::fmod(rotateDeg, 360.0) == 0.0;
  return noTranslation && noRotation3d && noRotation2d && scale == 1.0 && matrixIsIdentity();
}

namespace {

using Reader = SceneReader;

constexpr SceneKey<Scene> kDocumentKeys[] = {
    {"version",
     [](const Reader& r, const json& x, const std::string& p, Scene& s, int) {
       s.version = r.integer(x, p, INT_MIN, INT_MAX);
       if (s.version != 1)
         r.fail(p, "unsupported scene version " + std::to_string(s.version) + " (this program reads version 1)");
     },
     [](const Scene& s, int) -> Written { return s.version; },
     [](const Reader& r, const std::string& p, Scene&, int) { r.fail(p, "missing (required; this program reads scene version 1)"); }},
    {"mode", [](const Reader& r, const json& x, const std::string& p, Scene& s, int) { s.mode = r.choice<SceneMode>(x, p, kSceneModeNames); },
     [](const Scene& s, int) -> Written { return std::string(sceneModeName(s.mode)); },
     [](const Reader& r, const std::string& p, Scene&, int) {
       r.fail(p, "missing (required; one of: " + namesIn<SceneMode>(kSceneModeNames) + ")");
     }},
    {"data", [](const Reader& r, const json& x, const std::string&, Scene& s, int) { s.data = readDataSection(r, x, s.dimension()); },
     [](const Scene& s, int dim) -> Written { return writeObject(s.data, dataKeys(), dim); },
     [](const Reader& r, const std::string& p, Scene& s, int) {
       if (s.mode == SceneMode::Patch || s.mode == SceneMode::HoleFill) {
         s.data.preset = "sphere6";  // unused by the patch editor and hole filling
         return;
       }
       r.fail(p, "missing (required: {\"preset\": NAME}, {\"file\": PATH} or {\"points\": [...], \"normals\": [...]})");
     }},
    {"fit", [](const Reader& r, const json& x, const std::string& p, Scene& s, int) { s.fit = readObject(r, x, p, fitKeys(), s.dimension()); },
     [](const Scene& s, int dim) -> Written { return writeObject(s.fit, fitKeys(), dim); }},
    {"transform",
     [](const Reader& r, const json& x, const std::string&, Scene& s, int) { s.transform = readTransformSection(r, x, s.dimension()); },
     [](const Scene& s, int dim) -> Written { return writeObject(s.transform, transformKeys(), dim); },
     [](const Reader&, const std::string&, Scene& s, int) { s.transform = defaultTransform(s.dimension()); }},
    {"view", [](const Reader& r, const json& x, const std::string& p, Scene& s, int) { s.view = readObject(r, x, p, viewKeys(), s.dimension()); },
     [](const Scene& s, int dim) -> Written { return writeObject(s.view, viewKeys(), dim); }},
    {"patch", [](const Reader& r, const json& x, const std::string& p, Scene& s, int) { s.patch = readObject(r, x, p, patchKeys(), 3); },
     [](const Scene& s, int dim) -> Written {
       return s.mode == SceneMode::Patch ? Written(writeObject(s.patch, patchKeys(), dim)) : std::nullopt;
     }},
    {"holefill",
     [](const Reader& r, const json& x, const std::string& p, Scene& s, int) { s.holefill = readObject(r, x, p, holeFillKeys(), 3); },
     [](const Scene& s, int dim) -> Written {
       return s.mode == SceneMode::HoleFill ? Written(writeObject(s.holefill, holeFillKeys(), dim)) : std::nullopt;
     }},
};

// 1-based line and column of the 1-based byte offset `byte` (nlohmann's parse_error::byte, the
// position of the character that made the parse fail).
std::pair<std::size_t, std::size_t> lineAndColumn(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(byte == 0 ? 0 : byte - 1, text.size());
  std::size_t line = 1;
  std::size_t lineStart = 0;
  for (std::size_t i = 0; i < end; ++i)
    if (text[i] == '\n') ++line, lineStart = i + 1;
  return {line, end - lineStart + 1};
}

// Strips nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ".
std::string parseErrorReason(const std::string& what) {
  std::string s = what;
  if (const auto p = s.find("] "); p != std::string::npos && s.rfind("[json.exception", 0) == 0)
    s = s.substr(p + 2);
  if (s.rfind("parse error", 0) == 0)
    if (const auto p = s.find(": "); p != std::string::npos) s = s.substr(p + 2);
  // nlohmann ends with "; last read: 'TOKEN'" (or quotes the number it could not parse), and a
  // token may be megabytes long.
  const std::string lastRead = "; last read: '";
  if (const auto p = s.find(lastRead); p != std::string::npos && s.size() > p + lastRead.size() && s.back() == '\'')
    s = s.substr(0, p) + "; last read: " +
        quotedToken(std::string_view(s).substr(p + lastRead.size(), s.size() - 1 - p - lastRead.size()));
  const std::string overflow = "number overflow parsing '";
  if (const auto p = s.find(overflow); p != std::string::npos && s.back() == '\'')
    s = "number overflow parsing " +
        quotedToken(std::string_view(s).substr(p + overflow.size(), s.size() - 1 - p - overflow.size()));
  return s;
}

}  // namespace

void applySetOverride(json& document, const std::string& keyEqualsValue) {
  const auto eq = keyEqualsValue.find('=');
  if (eq == std::string::npos)
    throw UsageError("--set '" + keyEqualsValue + "': expected KEY=VALUE (e.g. fit.kernel=cubic)");
  const std::string key = keyEqualsValue.substr(0, eq);
  const std::string valueText = keyEqualsValue.substr(eq + 1);
  if (key.empty())
    throw UsageError("--set '" + keyEqualsValue + "': the key before '=' is empty (e.g. fit.radius=0.5)");

  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const auto dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  for (const std::string& part : parts)
    if (part.empty())
      throw UsageError("--set '" + keyEqualsValue + "': the key '" + key +
                       "' has an empty component (write a.b.c)");

  json value = json::parse(valueText, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = valueText;

  if (document.is_null()) document = json::object();
  if (!document.is_object())
    throw InputError("--set " + key + ": the scene document is not a JSON object");
  json* node = &document;
  std::string path;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    path = childPath(path, parts[i]);
    json& child = (*node)[parts[i]];
    if (child.is_null()) child = json::object();
    if (!child.is_object())
      throw InputError("--set " + key + ": " + path + " is not an object (it is " + describeJson(child) +
                       "), so it cannot hold '" + parts[i + 1] + "'");
    node = &child;
  }
  (*node)[parts.back()] = std::move(value);
}

Scene parseScene(const json& document, const std::string& sourceName, const std::string& baseDirectory) {
  const SceneReader reader(sourceName, baseDirectory);
  checkKeys<Scene>(reader, document, "", kDocumentKeys);
  Scene scene;
  scene.sourceName = sourceName;
  readKeys<Scene>(reader, document, "", kDocumentKeys, scene, 0);
  return scene;
}

Scene loadSceneFile(const std::string& path, const std::vector<std::string>& overrides) {
  return parseSceneText(readInputFile(path, "scene"), path, overrides);
}

Scene parseSceneText(const std::string& text, const std::string& path, const std::vector<std::string>& overrides) {

  // Object keys must be unique: nlohmann would silently keep the last one.
  std::vector<std::set<std::string>> keysPerLevel;
  std::vector<std::string> keyPath;
  const json::parser_callback_t callback = [&](int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        keysPerLevel.emplace_back();
        break;
      case json::parse_event_t::object_end:
        if (!keysPerLevel.empty()) keysPerLevel.pop_back();
        if (keyPath.size() > keysPerLevel.size()) keyPath.resize(keysPerLevel.size());
        break;
      case json::parse_event_t::key: {
        const std::string k = parsed.get<std::string>();
        keyPath.resize(keysPerLevel.size());
        keyPath.back() = k;
        if (!keysPerLevel.back().insert(k).second) {
          std::string full;
          for (const std::string& part : keyPath) full = childPath(full, shortenedToken(part));
          throw InputError(path + ": " + full + ": duplicate key (each key may appear once per object)");
        }
        break;
      }
      default: break;
    }
    return true;
  };

  json document;
  try {
    document = json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    const auto [line, column] = lineAndColumn(text, e.byte);
    throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(column) +
                     ": JSON syntax error: " + parseErrorReason(e.what()));
  } catch (const json::out_of_range& e) {
    // A number beyond double range (1e400): nlohmann gives no position, the key path is known.
    std::string full;
    for (const std::string& part : keyPath) full = childPath(full, shortenedToken(part));
    throw InputError(path + ": " + (full.empty() ? "" : full + ": ") + "number out of range (" +
                     parseErrorReason(e.what()) + "); numbers must lie within ±1.7976931348623157e308");
  }
  for (const std::string& o : overrides) applySetOverride(document, o);
  const std::string base = std::filesystem::path(path).parent_path().string();
  return parseScene(document, path, base);
}

json sceneToJson(const Scene& scene) { return writeObject<Scene>(scene, kDocumentKeys, scene.dimension()); }

void saveSceneFile(const Scene& scene, const std::string& path) {
  // data.file and holefill.mesh name the same files from the scene's new folder.
  const Scene moved = withPathsRelativeTo(scene, std::filesystem::path(path).parent_path().string());
  writeFileAtomically(path, sceneToJson(moved).dump(2) + "\n");
}

}  // namespace hermite
