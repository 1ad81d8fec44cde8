// The keys of `patch` (mode "patch") and `holefill` (mode "holefill"), docs/scene-format.md.

#include "scene/scene_file.h"
#include "scene/scene_keys.h"

namespace hermite {

namespace {

using json = nlohmann::json;
using Reader = SceneReader;

Vec<3> vec3(const Reader& r, const json& v, const std::string& path) {
  const auto a = r.fixed<3>(v, path, "[x, y, z]");
  return Vec<3>(a[0], a[1], a[2]);
}

json vec3Json(const Vec<3>& x) { return json::array({x.x(), x.y(), x.z()}); }

KnotData readKnot(const Reader& r, const json& e, const std::string& path) {
  r.object(e, path, std::array<std::string_view, 4>{"X", "Xu", "Xv", "Xuv"});
  KnotData d;
  for (const auto& [key, target] :
       {std::pair{"X", &d.X}, std::pair{"Xu", &d.Xu}, std::pair{"Xv", &d.Xv}, std::pair{"Xuv", &d.Xuv}}) {
    const json* c = Reader::find(e, key);
    if (!c) r.fail(childPath(path, key), "missing (each knot has X, Xu, Xv and Xuv)");
    *target = vec3(r, *c, childPath(path, key));
  }
  return d;
}

// One knot per grid corner: (splits[0] + 1) × (splits[1] + 1), read after `splits`.
void readKnots(const Reader& r, const json& x, const std::string& p, PatchSpec& s, int) {
  if (!x.is_array()) r.fail(p, "must be an array of {X, Xu, Xv, Xuv} (got " + describeJson(x) + ")");
  const std::size_t want = std::size_t(s.splits[0] + 1) * std::size_t(s.splits[1] + 1);
  if (x.size() != want)
    r.fail(p, "must have (splits[0] + 1) × (splits[1] + 1) = " + std::to_string(want) + " entries (got " +
                  std::to_string(x.size()) + ")");
  for (std::size_t k = 0; k < x.size(); ++k) s.knots.push_back(readKnot(r, x[k], indexPath(p, k)));
}

Written writeKnots(const PatchSpec& s, int) {
  if (s.knots.empty()) return std::nullopt;
  json knots = json::array();
  for (const KnotData& k : s.knots)
    knots.push_back({{"X", vec3Json(k.X)}, {"Xu", vec3Json(k.Xu)}, {"Xv", vec3Json(k.Xv)}, {"Xuv", vec3Json(k.Xuv)}});
  return knots;
}

void readSplits(const Reader& r, const json& x, const std::string& p, PatchSpec& s, int) {
  if (!x.is_array() || x.size() != 2) r.fail(p, "must be [n, m] (got " + describeJson(x) + ")");
  s.splits = {r.integer(x[0], indexPath(p, 0), 1, 16), r.integer(x[1], indexPath(p, 1), 1, 16)};
}

void readDomain(const Reader& r, const json& x, const std::string& p, PatchSpec& s, int) {
  s.domain = r.fixed<4>(x, p, "[U0, U1, V0, V1]");
  if (!(s.domain[0] < s.domain[1]) || !(s.domain[2] < s.domain[3])) r.fail(p, "must satisfy U0 < U1 and V0 < V1");
}

constexpr SceneKey<PatchSpec> kPatchKeys[] = {
    {"preset", [](const Reader& r, const json& x, const std::string& p, PatchSpec& s, int) { s.preset = r.listed(x, p, patchPresets()); },
     [](const PatchSpec& s, int) -> Written { return s.preset; }},
    {"splits", readSplits, [](const PatchSpec& s, int) -> Written { return s.splits; }},
    {"domain", readDomain, [](const PatchSpec& s, int) -> Written { return s.domain; }},
    enumKey<PatchSpec, &PatchSpec::form, kPatchFormNames>("form"),
    valueKey<PatchSpec, &PatchSpec::showError, &Reader::boolean>("show_error"),
    valueKey<PatchSpec, &PatchSpec::showIsoLines, &Reader::boolean>("show_iso_lines"),
    valueKey<PatchSpec, &PatchSpec::showHandles, &Reader::boolean>("show_handles"),
    integerKey<PatchSpec, &PatchSpec::tessellation, 2, 256>("tessellation"),
    {"knots", readKnots, writeKnots},
};

constexpr SceneKey<HoleFillSpec> kHoleFillKeys[] = {
    {"mesh",
     [](const Reader& r, const json& x, const std::string& p, HoleFillSpec& h, int) {
       h.mesh = r.string(x, p);
       if (h.mesh.empty()) r.fail(p, "must be a file name (or leave the key out for the preset)");
       h.resolvedMesh = r.resolvePath(h.mesh);
     },
     [](const HoleFillSpec& h, int) -> Written { return h.mesh.empty() ? Written() : json(h.mesh); }},
    {"preset", [](const Reader& r, const json& x, const std::string& p, HoleFillSpec& h, int) { h.preset = r.listed(x, p, holeFillPresets()); },
     [](const HoleFillSpec& h, int) -> Written { return h.preset; }},
    enumKey<HoleFillSpec, &HoleFillSpec::stage, kHoleFillStageNames>("stage"),
    enumKey<HoleFillSpec, &HoleFillSpec::implicit, kHoleImplicitNames>("implicit"),
    integerKey<HoleFillSpec, &HoleFillSpec::rings, 1, 10>("rings"),
};

}  // namespace

std::span<const SceneKey<PatchSpec>> patchKeys() { return kPatchKeys; }
std::span<const SceneKey<HoleFillSpec>> holeFillKeys() { return kHoleFillKeys; }

}  // namespace hermite
