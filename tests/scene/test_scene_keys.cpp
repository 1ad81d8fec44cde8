#include <doctest/doctest.h>

#include <set>
#include <string>

#include "core/base/errors.h"
#include "scene/scene_file.h"
#include "scene/scene_keys.h"

using nlohmann::json;

namespace {

// A scene of each mode with every optional key set, written out in full.
std::vector<json> fullDocuments() {
  const json base = {{"version", 1}, {"data", {{"preset", "sphere6"}}}};
  json t3 = base;
  t3["mode"] = "implicit3d";
  t3["transform"] = {{"matrix", {1, 0, 0, 0, 2, 0, 0, 0, 1}}, {"verify", true}};
  t3["view"] = {{"bounds", {-1, -1, -1, 1, 1, 1}}};
  json t2 = base;
  t2["mode"] = "implicit2d";
  t2["data"] = {{"points", {{0, 1}, {1, 0}}}, {"normals", {{0, 1}, {1, 0}}}};
  json patch = base;
  patch["mode"] = "patch";
  patch["patch"] = {{"splits", {1, 1}}};
  json knot = {{"X", {0, 0, 0}}, {"Xu", {1, 0, 0}}, {"Xv", {0, 1, 0}}, {"Xuv", {0, 0, 0}}};
  patch["patch"]["knots"] = {knot, knot, knot, knot};
  json hole = base;
  hole["mode"] = "holefill";
  hole["holefill"] = {{"mesh", "m.off"}};
  json file = base;
  file["mode"] = "implicit3d";
  file["data"] = {{"file", "p.xyz"}, {"orient_normals", false}};
  std::vector<json> out;
  for (const json& d : {t3, t2, patch, hole, file}) out.push_back(hermite::sceneToJson(hermite::parseScene(d, "k.json", "")));
  return out;
}

template <class Spec>
void checkTable(const std::string& path, std::span<const hermite::SceneKey<Spec>> keys) {
  CAPTURE(path);
  const std::vector<json> docs = fullDocuments();
  std::set<std::string> table, written;
  for (const auto& k : keys) table.insert(std::string(k.name));
  for (const json& d : docs) {
    const json::json_pointer p("/" + path);
    if (!d.contains(p)) continue;
    for (const auto& item : d[p].items()) written.insert(item.key());
  }
  // The writer emits only the table's keys, and every key of the table in some scene.
  CHECK(written == table);
  // The reader allows exactly the table's keys: an unknown key's message lists them in table order.
  json doc = docs.front();
  if (path == "patch" || path == "holefill") doc = docs[path == "patch" ? 2 : 3];
  doc[json::json_pointer("/" + path)]["zz_unknown"] = 1;
  std::string expected;
  for (const auto& k : keys) expected += (expected.empty() ? "" : ", ") + std::string(k.name);
  const std::string dotted = path + ".zz_unknown";
  CHECK_THROWS_WITH_AS(hermite::parseScene(doc, "k.json", ""),
                       ("k.json: " + dotted + ": unknown key (expected one of: " + expected + ")").c_str(),
                       hermite::InputError);
}

}  // namespace

TEST_CASE("scene keys: each object's table is what the reader allows and what the writer emits") {
  checkTable<hermite::DataSpec>("data", hermite::dataKeys());
  checkTable<hermite::FitSpec>("fit", hermite::fitKeys());
  checkTable<hermite::TransformSpec>("transform", hermite::transformKeys());
  checkTable<hermite::ViewSpec>("view", hermite::viewKeys());
  checkTable<hermite::PatchSpec>("patch", hermite::patchKeys());
  checkTable<hermite::HoleFillSpec>("holefill", hermite::holeFillKeys());
}

TEST_CASE("scene keys: enum names come from one table, both ways") {
  for (const auto& e : hermite::kSceneModeNames) {
    CHECK(hermite::sceneModeName(e.value) == e.name);
    CHECK(hermite::valueIn<hermite::SceneMode>(hermite::kSceneModeNames, e.name) == e.value);
  }
  for (const auto& e : hermite::kPolynomialNames) CHECK(hermite::parsePolynomial(e.name) == e.value);
  for (const auto& e : hermite::kSolverChoiceNames) CHECK(hermite::parseSolverChoice(e.name) == e.value);
  for (const auto& e : hermite::kPuBlendNames) CHECK(hermite::parsePuBlend(e.name) == e.value);
  CHECK_THROWS_WITH_AS(hermite::parsePolynomial("cubic"),
                       "unknown polynomial 'cubic', expected one of: none, linear, quadratic", hermite::InputError);
  CHECK_THROWS_WITH_AS(hermite::parsePuBlend("soft"), "unknown blend 'soft' (expected smooth or hard)",
                       hermite::InputError);
}
