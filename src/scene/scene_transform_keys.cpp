// The keys of `transform` (docs/scene-format.md): 2D scenes rotate by one angle, 3D scenes about
// an axis; `matrix` is a general invertible linear map applied after scale and rotation.

#include <algorithm>
#include <cmath>

#include "core/base/format_number.h"
#include "scene/scene_file.h"
#include "scene/scene_keys.h"

namespace hermite {

namespace {

using json = nlohmann::json;
using Reader = SceneReader;

void readMatrix(const Reader& r, const json& x, const std::string& p, TransformSpec& t, int dim) {
  const std::size_t n = std::size_t(dim) * std::size_t(dim);
  t.matrix = r.numbers(x, p, n, dim == 2 ? "[m00, m01, m10, m11] (row-major)" : "9 numbers, row-major");
  const auto& m = t.matrix;
  const double det = dim == 2 ? m[0] * m[3] - m[1] * m[2]
                              : m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                                    m[2] * (m[3] * m[7] - m[4] * m[6]);
  double norm = 0;
  for (double e : m) norm = std::max(norm, std::abs(e));
  if (!(std::abs(det) > 1e-12 * std::pow(norm, dim)))
    r.fail(p, "must be invertible (its determinant is " + formatNumber(det) + ")");
}

void readAxisAngle(const Reader& r, const json& x, const std::string& p, TransformSpec& t, int) {
  t.rotateAxisAngleDeg = r.fixed<4>(x, p, "[ax, ay, az, degrees]");
  const auto& a = t.rotateAxisAngleDeg;
  if (a[0] == 0 && a[1] == 0 && a[2] == 0) r.fail(p, "the axis (first three numbers) must be non-zero");
}

json translateJson(const TransformSpec& t, int dim) {
  json translate = json::array();
  for (std::size_t i = 0; i < std::size_t(dim); ++i) translate.push_back(i < t.translate.size() ? t.translate[i] : 0.0);
  return translate;
}

constexpr SceneKey<TransformSpec> kTransformKeys[] = {
    {"translate",
     [](const Reader& r, const json& x, const std::string& p, TransformSpec& t, int dim) {
       t.translate = r.numbers(x, p, std::size_t(dim), dim == 2 ? "[x, y] in a 2D scene" : "[x, y, z] in a 3D scene");
     },
     [](const TransformSpec& t, int dim) -> Written { return translateJson(t, dim); }},
    {"rotate_axis_angle_deg", readAxisAngle,
     [](const TransformSpec& t, int dim) -> Written { return dim == 3 ? json(t.rotateAxisAngleDeg) : Written(); }},
    {"rotate_deg", [](const Reader& r, const json& x, const std::string& p, TransformSpec& t, int) { t.rotateDeg = r.number(x, p); },
     [](const TransformSpec& t, int dim) -> Written { return dim == 2 ? json(t.rotateDeg) : Written(); }},
    valueKey<TransformSpec, &TransformSpec::scale, &Reader::positive>("scale"),
    enumKey<TransformSpec, &TransformSpec::method, kTransformMethodNames>("method"),
    {"matrix", readMatrix, [](const TransformSpec& t, int) -> Written { return t.matrix.empty() ? Written() : json(t.matrix); }},
    {"verify", [](const Reader& r, const json& x, const std::string& p, TransformSpec& t, int) { t.verify = r.boolean(x, p); },
     [](const TransformSpec& t, int) -> Written { return t.verify ? json(true) : Written(); }},
};

// The rotation key of the other dimension is refused before any value is read.
void checkRotationKey(const Reader& r, const json& v, int dim) {
  if (dim == 2 && Reader::find(v, "rotate_axis_angle_deg"))
    r.fail("transform.rotate_axis_angle_deg",
           "not available in a 2D scene (mode implicit2d); use transform.rotate_deg (one angle in "
           "degrees, counter-clockwise)");
  if (dim == 3 && Reader::find(v, "rotate_deg"))
    r.fail("transform.rotate_deg",
           "only for 2D scenes (mode implicit2d); use transform.rotate_axis_angle_deg "
           "[ax, ay, az, degrees] in a 3D scene");
}

}  // namespace

std::span<const SceneKey<TransformSpec>> transformKeys() { return kTransformKeys; }

TransformSpec defaultTransform(int dim) {
  TransformSpec t;
  t.translate.assign(static_cast<std::size_t>(dim), 0.0);
  return t;
}

TransformSpec readTransformSection(const SceneReader& reader, const json& v, int dim) {
  checkKeys<TransformSpec>(reader, v, "transform", kTransformKeys);
  checkRotationKey(reader, v, dim);
  TransformSpec t = defaultTransform(dim);
  readKeys<TransformSpec>(reader, v, "transform", kTransformKeys, t, dim);
  return t;
}

}  // namespace hermite
