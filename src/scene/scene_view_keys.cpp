// The keys of `view` and its objects `camera`, `view2d` and `slice` (docs/scene-format.md).

#include <cmath>

#include "scene/scene_file.h"
#include "scene/scene_keys.h"
#include "scene/view_bounds.h"

namespace hermite {

namespace {

using json = nlohmann::json;
using Reader = SceneReader;

// The camera basis needs target ≠ eye and an up vector not parallel to the view direction.
void checkCameraBasis(const Reader& r, const std::string& path, const CameraSpec& c) {
  const double f[3] = {c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]};
  if (f[0] == 0 && f[1] == 0 && f[2] == 0)
    r.fail(childPath(path, "target"),
           "must differ from " + childPath(path, "eye") + " (the view direction is target - eye)");
  const double cross[3] = {f[1] * c.up[2] - f[2] * c.up[1], f[2] * c.up[0] - f[0] * c.up[2],
                           f[0] * c.up[1] - f[1] * c.up[0]};
  const double fNorm = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  const double upNorm = std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]);
  const double crossNorm = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  // sin of the angle between up and the view direction; below 1e-9 the camera basis is undefined.
  if (upNorm == 0 || !(crossNorm > 1e-9 * fNorm * upNorm))
    r.fail(childPath(path, "up"), "must be non-zero and not parallel to the view direction target - eye");
}

constexpr SceneKey<CameraSpec> kCameraKeys[] = {
    {"eye", [](const Reader& r, const json& x, const std::string& p, CameraSpec& c, int) { c.eye = r.fixed<3>(x, p, "[x, y, z]"); },
     [](const CameraSpec& c, int) -> Written { return c.eye; }},
    {"target", [](const Reader& r, const json& x, const std::string& p, CameraSpec& c, int) { c.target = r.fixed<3>(x, p, "[x, y, z]"); },
     [](const CameraSpec& c, int) -> Written { return c.target; }},
    {"up", [](const Reader& r, const json& x, const std::string& p, CameraSpec& c, int) { c.up = r.fixed<3>(x, p, "[x, y, z]"); },
     [](const CameraSpec& c, int) -> Written { return c.up; }},
    {"fov_y_deg",
     [](const Reader& r, const json& x, const std::string& p, CameraSpec& c, int) {
       c.fovYDeg = r.number(x, p);
       if (!(c.fovYDeg > 0 && c.fovYDeg < 180)) r.fail(p, "must be in (0, 180) degrees (got " + describeJson(x) + ")");
     },
     [](const CameraSpec& c, int) -> Written { return c.fovYDeg; }},
};

constexpr SceneKey<SliceSpec> kSliceKeys[] = {
    valueKey<SliceSpec, &SliceSpec::enabled, &Reader::boolean>("enabled"),
    {"normal",
     [](const Reader& r, const json& x, const std::string& p, SliceSpec& s, int) {
       s.normal = r.fixed<3>(x, p, "[nx, ny, nz]");
       if (s.normal[0] == 0 && s.normal[1] == 0 && s.normal[2] == 0) r.fail(p, "must be non-zero");
     },
     [](const SliceSpec& s, int) -> Written { return s.normal; }},
    valueKey<SliceSpec, &SliceSpec::offset, &Reader::number>("offset"),
};

constexpr SceneKey<ViewSpec> kView2dKeys[] = {
    {"center", [](const Reader& r, const json& x, const std::string& p, ViewSpec& v, int) { v.center2d = r.fixed<2>(x, p, "[x, y]"); },
     [](const ViewSpec& v, int) -> Written { return v.center2d; }},
    valueKey<ViewSpec, &ViewSpec::halfHeight2d, &Reader::positive>("half_height"),
};

void readSize(const Reader& r, const json& x, const std::string& p, ViewSpec& v, int) {
  if (!x.is_array() || x.size() != 2)
    r.fail(p, "must be an array of 2 integers [width, height] (got " + describeJson(x) + ")");
  for (std::size_t i = 0; i < 2; ++i) v.size[i] = r.integer(x[i], indexPath(p, i), 1, 16384);
}

void readBackground(const Reader& r, const json& x, const std::string& p, ViewSpec& v, int) {
  v.background = r.fixed<3>(x, p, "[r, g, b]");
  for (std::size_t i = 0; i < 3; ++i)
    if (v.background[i] < 0 || v.background[i] > 1)
      r.fail(indexPath(p, i), "must be in [0, 1] (got " + describeJson(x[i]) + ")");
}

void readBounds(const Reader& r, const json& x, const std::string& p, ViewSpec& v, int dim) {
  if (x.is_null()) return;
  const std::string shape = dim == 2 ? "[xmin, ymin, xmax, ymax] or null in a 2D scene"
                                     : "[xmin, ymin, zmin, xmax, ymax, zmax] or null in a 3D scene";
  std::vector<double> b = r.numbers(x, p, 2 * static_cast<std::size_t>(dim), shape);
  if (const std::string problem = viewBoundsProblem(b, dim); !problem.empty()) r.fail(p, problem);
  v.bounds = std::move(b);
}

// true, false or "auto" (none).
void readShowNormals(const Reader& r, const json& x, const std::string& p, ViewSpec& v, int) {
  if (x.is_boolean())
    v.showNormals = x.get<bool>();
  else if (x.is_string() && x.get<std::string>() == "auto")
    v.showNormals.reset();
  else
    r.fail(p, "must be true, false or \"auto\" (got " + describeJson(x) + ")");
}

void readCamera(const Reader& r, const json& x, const std::string& p, ViewSpec& v, int dim) {
  v.camera = readObject<CameraSpec>(r, x, p, kCameraKeys, dim);
  checkCameraBasis(r, p, v.camera);
}

void readView2d(const Reader& r, const json& x, const std::string& p, ViewSpec& v, int dim) {
  checkKeys<ViewSpec>(r, x, p, kView2dKeys);
  readKeys<ViewSpec>(r, x, p, kView2dKeys, v, dim);
}

constexpr SceneKey<ViewSpec> kViewKeys[] = {
    {"size", readSize, [](const ViewSpec& v, int) -> Written { return v.size; }},
    {"background", readBackground, [](const ViewSpec& v, int) -> Written { return v.background; }},
    {"bounds", readBounds, [](const ViewSpec& v, int) -> Written { return v.bounds ? json(*v.bounds) : json(nullptr); }},
    enumKey<ViewSpec, &ViewSpec::projection, kProjectionNames>("projection"),
    {"camera", readCamera, [](const ViewSpec& v, int dim) -> Written { return writeObject<CameraSpec>(v.camera, kCameraKeys, dim); }},
    {"view2d", readView2d, [](const ViewSpec& v, int dim) -> Written { return writeObject<ViewSpec>(v, kView2dKeys, dim); }},
    valueKey<ViewSpec, &ViewSpec::showPoints, &Reader::boolean>("show_points"),
    {"show_normals", readShowNormals,
     [](const ViewSpec& v, int) -> Written { return v.showNormals ? json(*v.showNormals) : json("auto"); }},
    valueKey<ViewSpec, &ViewSpec::showBounds, &Reader::boolean>("show_bounds"),
    valueKey<ViewSpec, &ViewSpec::showAxes, &Reader::boolean>("show_axes"),
    valueKey<ViewSpec, &ViewSpec::presenter, &Reader::boolean>("presenter"),
    enumKey<ViewSpec, &ViewSpec::ground, kGroundNames>("ground"),
    enumKey<ViewSpec, &ViewSpec::trace, kTraceModeNames>("trace"),
    {"slice",
     [](const Reader& r, const json& x, const std::string& p, ViewSpec& v, int dim) { v.slice = readObject<SliceSpec>(r, x, p, kSliceKeys, dim); },
     [](const ViewSpec& v, int dim) -> Written { return writeObject<SliceSpec>(v.slice, kSliceKeys, dim); }},
};

}  // namespace

std::span<const SceneKey<ViewSpec>> viewKeys() { return kViewKeys; }

}  // namespace hermite
