#include "scene/scene_file.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>
#include <utility>

#include "core/base/errors.h"
#include "core/base/format_number.h"
#include "io/atomic_file.h"
#include "scene/view_bounds.h"

namespace hermite {

using json = nlohmann::json;

std::string_view sceneModeName(SceneMode m) {
  switch (m) {
    case SceneMode::Implicit2d: return "implicit2d";
    case SceneMode::Implicit3d: return "implicit3d";
    case SceneMode::Patch: return "patch";
    case SceneMode::HoleFill: return "holefill";
  }
  return "implicit3d";
}

std::string_view fitMethodName(FitMethod m) {
  switch (m) {
    case FitMethod::Hrbf: return "hrbf";
    case FitMethod::RbfOffset: return "rbf-offset";
  }
  return "hrbf";
}

std::string_view projectionName(Projection p) {
  switch (p) {
    case Projection::Perspective: return "perspective";
    case Projection::Orthographic: return "orthographic";
  }
  return "perspective";
}

std::string_view traceModeName(TraceMode t) {
  switch (t) {
    case TraceMode::Auto: return "auto";
    case TraceMode::Baked: return "baked";
    case TraceMode::Exact: return "exact";
  }
  return "auto";
}

std::string_view transformMethodName(TransformMethod m) {
  switch (m) {
    case TransformMethod::Auto: return "auto";
    case TransformMethod::Update: return "update";
    case TransformMethod::Resolve: return "re-solve";
  }
  return "auto";
}

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

// A short description of a JSON value for "(got ...)" in messages.
std::string describe(const json& v) {
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

std::string joinNames(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string childPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string indexPath(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// Reads the values of one scene document, throwing "<source>: <key.path>: <expected>".
class SceneReader {
 public:
  SceneReader(std::string source, std::string baseDirectory)
      : source_(std::move(source)), baseDirectory_(std::move(baseDirectory)) {}

  Scene read(const json& document) const;

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(source_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }

  // Checks that `v` is an object whose keys are all in `keys`.
  void object(const json& v, const std::string& path, std::initializer_list<std::string_view> keys) const;
  static const json* find(const json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  double number(const json& v, const std::string& path) const;
  double positive(const json& v, const std::string& path) const;
  double nonNegative(const json& v, const std::string& path) const;
  int integer(const json& v, const std::string& path, int lo, int hi) const;
  bool boolean(const json& v, const std::string& path) const;
  std::string string(const json& v, const std::string& path) const;
  std::vector<double> numbers(const json& v, const std::string& path, std::size_t n,
                              std::string_view shape) const;
  template <std::size_t N>
  std::array<double, N> fixed(const json& v, const std::string& path, std::string_view shape) const {
    const std::vector<double> values = numbers(v, path, N, shape);
    std::array<double, N> out{};
    std::copy(values.begin(), values.end(), out.begin());
    return out;
  }
  template <class E>
  E choice(const json& v, const std::string& path,
           std::initializer_list<std::pair<std::string_view, E>> options) const;
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

  SceneMode readMode(const json& v) const;
  DataSpec readData(const json& v, int dim) const;
  std::vector<std::vector<double>> readVectors(const json& v, const std::string& path, int dim) const;
  FitSpec readFit(const json& v) const;
  PartitionSpec readPartition(const json& v, const std::string& path) const;
  TransformSpec readTransform(const json& v, int dim) const;
  ViewSpec readView(const json& v, int dim) const;
  CameraSpec readCamera(const json& v, const std::string& path) const;
  SliceSpec readSlice(const json& v, const std::string& path) const;
  PatchSpec readPatch(const json& v) const;
  HoleFillSpec readHoleFill(const json& v) const;
  Vec<3> vec3(const json& v, const std::string& path) const;

  std::string source_;
  std::string baseDirectory_;
};

void SceneReader::object(const json& v, const std::string& path,
                         std::initializer_list<std::string_view> keys) const {
  if (!v.is_object()) {
    if (path.empty()) fail("", "the scene must be a JSON object (got " + describe(v) + ")");
    fail(path, "must be an object (got " + describe(v) + ")");
  }
  for (const auto& item : v.items()) {
    const std::string& key = item.key();
    if (std::find(keys.begin(), keys.end(), std::string_view(key)) != keys.end()) continue;
    std::string what = "unknown key (expected one of: " + joinNames(keys) + ")";
    std::string_view best;
    std::size_t bestDistance = 3;
    for (std::string_view k : keys) {
      const std::size_t d = editDistance(key, k);
      if (d < bestDistance) bestDistance = d, best = k;
    }
    if (!best.empty()) what += "; did you mean '" + std::string(best) + "'?";
    fail(childPath(path, key), what);
  }
}

double SceneReader::number(const json& v, const std::string& path) const {
  if (!v.is_number()) fail(path, "must be a number (got " + describe(v) + ")");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path, "must be a finite number (got " + describe(v) + ")");
  return d;
}

double SceneReader::positive(const json& v, const std::string& path) const {
  const double d = number(v, path);
  if (!(d > 0)) fail(path, "must be > 0 (got " + describe(v) + ")");
  return d;
}

double SceneReader::nonNegative(const json& v, const std::string& path) const {
  const double d = number(v, path);
  if (!(d >= 0)) fail(path, "must be >= 0 (got " + describe(v) + ")");
  return d;
}

int SceneReader::integer(const json& v, const std::string& path, int lo, int hi) const {
  auto range = [&] {
    if (lo == INT_MIN && hi == INT_MAX) return "must be an integer in the 32-bit range (got " + describe(v) + ")";
    if (hi == INT_MAX) return "must be >= " + std::to_string(lo) + " (got " + describe(v) + ")";
    return "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " +
           describe(v) + ")";
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
    if (!std::isfinite(d) || d != std::floor(d))
      fail(path, "must be an integer (got " + describe(v) + ")");
    if (d < lo || d > hi) fail(path, range());
    value = static_cast<long long>(d);
  } else {
    fail(path, "must be an integer (got " + describe(v) + ")");
  }
  if (value < lo || value > hi) fail(path, range());
  return static_cast<int>(value);
}

bool SceneReader::boolean(const json& v, const std::string& path) const {
  if (!v.is_boolean()) fail(path, "must be true or false (got " + describe(v) + ")");
  return v.get<bool>();
}

std::string SceneReader::string(const json& v, const std::string& path) const {
  if (!v.is_string()) fail(path, "must be a string (got " + describe(v) + ")");
  return v.get<std::string>();
}

std::vector<double> SceneReader::numbers(const json& v, const std::string& path, std::size_t n,
                                         std::string_view shape) const {
  if (!v.is_array() || v.size() != n)
    fail(path, "must be an array of " + std::to_string(n) + " numbers " + std::string(shape) +
                   " (got " + describe(v) + ")");
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = number(v[i], indexPath(path, i));
  return out;
}

template <class E>
E SceneReader::choice(const json& v, const std::string& path,
                      std::initializer_list<std::pair<std::string_view, E>> options) const {
  const std::string name = string(v, path);
  std::string valid;
  for (const auto& [optionName, value] : options) {
    if (optionName == name) return value;
    valid += (valid.empty() ? "" : ", ") + std::string(optionName);
  }
  fail(path, "must be one of: " + valid + " (got " + describe(v) + ")");
}

SceneMode SceneReader::readMode(const json& v) const {
  return choice<SceneMode>(v, "mode",
                           {{"implicit2d", SceneMode::Implicit2d},
                            {"implicit3d", SceneMode::Implicit3d},
                            {"patch", SceneMode::Patch},
                            {"holefill", SceneMode::HoleFill}});
}

std::vector<std::vector<double>> SceneReader::readVectors(const json& v, const std::string& path,
                                                          int dim) const {
  if (!v.is_array()) fail(path, "must be an array of [" + std::string(dim == 2 ? "x, y" : "x, y, z") +
                                    "] entries (got " + describe(v) + ")");
  const std::string shape = dim == 2 ? "(2D scene)" : "(3D scene)";
  std::vector<std::vector<double>> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out.push_back(numbers(v[i], indexPath(path, i), static_cast<std::size_t>(dim), shape));
  return out;
}

DataSpec SceneReader::readData(const json& v, int dim) const {
  object(v, "data", {"preset", "count", "file", "points", "normals"});
  DataSpec data;
  const json* preset = find(v, "preset");
  const json* count = find(v, "count");
  const json* file = find(v, "file");
  const json* points = find(v, "points");
  const json* normals = find(v, "normals");

  std::vector<std::string> sources;
  if (preset) sources.push_back("data.preset");
  if (file) sources.push_back("data.file");
  if (points || normals) sources.push_back(points ? "data.points" : "data.normals");
  const std::string forms =
      "{\"preset\": NAME, \"count\": N}, {\"file\": PATH} or {\"points\": [...], \"normals\": [...]}";
  if (sources.empty()) fail("data", "no data source (expected one of " + forms + ")");
  if (sources.size() > 1) {
    std::string found;
    for (std::size_t i = 0; i < sources.size(); ++i)
      found += (i == 0 ? "" : i + 1 == sources.size() ? " and " : ", ") + sources[i];
    fail("data", "give exactly one data source, found " + found + " (expected one of " + forms + ")");
  }
  if (count && !preset) fail("data.count", "only allowed together with data.preset");

  if (preset) {
    data.preset = string(*preset, "data.preset");
    if (data.preset.empty()) fail("data.preset", "must be a non-empty preset name");
    if (count) data.count = integer(*count, "data.count", 0, INT_MAX);
  } else if (file) {
    data.file = string(*file, "data.file");
    if (data.file.empty()) fail("data.file", "must be a non-empty path");
    const std::filesystem::path p(data.file);
    data.resolvedFile = p.is_absolute() || baseDirectory_.empty()
                            ? data.file
                            : (std::filesystem::path(baseDirectory_) / p).string();
  } else {
    if (!points) fail("data.points", "missing: inline data needs both data.points and data.normals");
    if (!normals) fail("data.normals", "missing: inline data needs both data.points and data.normals");
    data.points = readVectors(*points, "data.points", dim);
    data.normals = readVectors(*normals, "data.normals", dim);
    if (data.points.size() != data.normals.size())
      fail("data.normals", "has " + std::to_string(data.normals.size()) + " entries but data.points has " +
                               std::to_string(data.points.size()) + " (one normal per point)");
  }
  return data;
}

PartitionSpec SceneReader::readPartition(const json& v, const std::string& path) const {
  object(v, path, {"enabled", "max_points_per_box", "box_size", "overlap", "blend"});
  PartitionSpec p;
  if (const json* x = find(v, "enabled")) p.enabled = boolean(*x, childPath(path, "enabled"));
  if (const json* x = find(v, "max_points_per_box"))
    p.maxPointsPerBox = integer(*x, childPath(path, "max_points_per_box"), 1, INT_MAX);
  if (const json* x = find(v, "box_size")) p.boxSize = nonNegative(*x, childPath(path, "box_size"));
  if (const json* x = find(v, "overlap")) {
    const std::string key = childPath(path, "overlap");
    p.overlap = number(*x, key);
    if (!(p.overlap >= 1)) fail(key, "must be >= 1 (got " + describe(*x) + ")");
  }
  if (const json* x = find(v, "blend")) p.blend = named(*x, childPath(path, "blend"), parsePuBlend);
  return p;
}

FitSpec SceneReader::readFit(const json& v) const {
  object(v, "fit",
         {"method", "kernel", "radius", "polynomial", "smoothing", "shift", "solver", "partition"});
  FitSpec fit;
  if (const json* x = find(v, "method"))
    fit.method = choice<FitMethod>(*x, "fit.method",
                                   {{"hrbf", FitMethod::Hrbf}, {"rbf-offset", FitMethod::RbfOffset}});
  if (const json* x = find(v, "kernel")) fit.kernel = named(*x, "fit.kernel", parseKernelType);
  if (const json* x = find(v, "radius")) fit.radius = positive(*x, "fit.radius");
  if (const json* x = find(v, "polynomial")) fit.polynomial = named(*x, "fit.polynomial", parsePolynomial);
  if (const json* x = find(v, "smoothing")) fit.smoothing = nonNegative(*x, "fit.smoothing");
  if (const json* x = find(v, "shift")) fit.shift = positive(*x, "fit.shift");
  if (const json* x = find(v, "solver")) fit.solver = named(*x, "fit.solver", parseSolverChoice);
  if (const json* x = find(v, "partition")) fit.partition = readPartition(*x, "fit.partition");
  return fit;
}

TransformSpec SceneReader::readTransform(const json& v, int dim) const {
  object(v, "transform", {"translate", "rotate_axis_angle_deg", "rotate_deg", "scale", "method", "matrix", "verify"});
  TransformSpec t;
  t.translate.assign(static_cast<std::size_t>(dim), 0.0);
  if (dim == 2) {
    if (find(v, "rotate_axis_angle_deg"))
      fail("transform.rotate_axis_angle_deg",
           "not available in a 2D scene (mode implicit2d); use transform.rotate_deg (one angle in "
           "degrees, counter-clockwise)");
    if (const json* x = find(v, "translate"))
      t.translate = numbers(*x, "transform.translate", 2, "[x, y] in a 2D scene");
    if (const json* x = find(v, "rotate_deg")) t.rotateDeg = number(*x, "transform.rotate_deg");
  } else {
    if (find(v, "rotate_deg"))
      fail("transform.rotate_deg",
           "only for 2D scenes (mode implicit2d); use transform.rotate_axis_angle_deg "
           "[ax, ay, az, degrees] in a 3D scene");
    if (const json* x = find(v, "translate"))
      t.translate = numbers(*x, "transform.translate", 3, "[x, y, z] in a 3D scene");
    if (const json* x = find(v, "rotate_axis_angle_deg")) {
      t.rotateAxisAngleDeg =
          fixed<4>(*x, "transform.rotate_axis_angle_deg", "[ax, ay, az, degrees]");
      const auto& r = t.rotateAxisAngleDeg;
      if (r[0] == 0 && r[1] == 0 && r[2] == 0)
        fail("transform.rotate_axis_angle_deg", "the axis (first three numbers) must be non-zero");
    }
  }
  if (const json* x = find(v, "scale")) t.scale = positive(*x, "transform.scale");
  if (const json* x = find(v, "method"))
    t.method = choice<TransformMethod>(*x, "transform.method",
                                       {{"auto", TransformMethod::Auto}, {"update", TransformMethod::Update},
                                        {"re-solve", TransformMethod::Resolve}});
  if (const json* x = find(v, "verify")) t.verify = boolean(*x, "transform.verify");
  if (const json* x = find(v, "matrix")) {
    const std::size_t n = std::size_t(dim) * std::size_t(dim);
    t.matrix = numbers(*x, "transform.matrix", n, dim == 2 ? "[m00, m01, m10, m11] (row-major)" : "9 numbers, row-major");
    double det = 0;
    const auto& m = t.matrix;
    if (dim == 2) det = m[0] * m[3] - m[1] * m[2];
    else det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
    double norm = 0;
    for (double e : m) norm = std::max(norm, std::abs(e));
    if (!(std::abs(det) > 1e-12 * std::pow(norm, dim)))
      fail("transform.matrix", "must be invertible (its determinant is " + formatNumber(det) + ")");
  }
  return t;
}

CameraSpec SceneReader::readCamera(const json& v, const std::string& path) const {
  object(v, path, {"eye", "target", "up", "fov_y_deg"});
  CameraSpec c;
  if (const json* x = find(v, "eye")) c.eye = fixed<3>(*x, childPath(path, "eye"), "[x, y, z]");
  if (const json* x = find(v, "target")) c.target = fixed<3>(*x, childPath(path, "target"), "[x, y, z]");
  if (const json* x = find(v, "up")) c.up = fixed<3>(*x, childPath(path, "up"), "[x, y, z]");
  if (const json* x = find(v, "fov_y_deg")) {
    const std::string key = childPath(path, "fov_y_deg");
    c.fovYDeg = number(*x, key);
    if (!(c.fovYDeg > 0 && c.fovYDeg < 180))
      fail(key, "must be in (0, 180) degrees (got " + describe(*x) + ")");
  }
  const double f[3] = {c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]};
  if (f[0] == 0 && f[1] == 0 && f[2] == 0)
    fail(childPath(path, "target"), "must differ from " + childPath(path, "eye") +
                                        " (the view direction is target - eye)");
  const double cross[3] = {f[1] * c.up[2] - f[2] * c.up[1], f[2] * c.up[0] - f[0] * c.up[2],
                           f[0] * c.up[1] - f[1] * c.up[0]};
  const double fNorm = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  const double upNorm = std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]);
  const double crossNorm = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  // sin of the angle between up and the view direction; below 1e-9 the camera basis is undefined.
  if (upNorm == 0 || !(crossNorm > 1e-9 * fNorm * upNorm))
    fail(childPath(path, "up"), "must be non-zero and not parallel to the view direction target - eye");
  return c;
}

SliceSpec SceneReader::readSlice(const json& v, const std::string& path) const {
  object(v, path, {"enabled", "normal", "offset"});
  SliceSpec s;
  if (const json* x = find(v, "enabled")) s.enabled = boolean(*x, childPath(path, "enabled"));
  if (const json* x = find(v, "normal")) {
    s.normal = fixed<3>(*x, childPath(path, "normal"), "[nx, ny, nz]");
    if (s.normal[0] == 0 && s.normal[1] == 0 && s.normal[2] == 0)
      fail(childPath(path, "normal"), "must be non-zero");
  }
  if (const json* x = find(v, "offset")) s.offset = number(*x, childPath(path, "offset"));
  return s;
}

ViewSpec SceneReader::readView(const json& v, int dim) const {
  object(v, "view", {"size", "background", "bounds", "projection", "camera", "view2d", "show_points",
                     "show_normals", "show_bounds", "trace", "slice"});
  ViewSpec view;
  if (const json* x = find(v, "size")) {
    if (!x->is_array() || x->size() != 2)
      fail("view.size", "must be an array of 2 integers [width, height] (got " + describe(*x) + ")");
    for (std::size_t i = 0; i < 2; ++i)
      view.size[i] = integer((*x)[i], indexPath("view.size", i), 1, 16384);
  }
  if (const json* x = find(v, "background")) {
    view.background = fixed<3>(*x, "view.background", "[r, g, b]");
    for (std::size_t i = 0; i < 3; ++i)
      if (view.background[i] < 0 || view.background[i] > 1)
        fail(indexPath("view.background", i),
             "must be in [0, 1] (got " + describe((*x)[i]) + ")");
  }
  if (const json* x = find(v, "bounds"); x && !x->is_null()) {
    const std::size_t n = 2 * static_cast<std::size_t>(dim);
    const std::string shape = dim == 2 ? "[xmin, ymin, xmax, ymax] or null in a 2D scene"
                                       : "[xmin, ymin, zmin, xmax, ymax, zmax] or null in a 3D scene";
    std::vector<double> b = numbers(*x, "view.bounds", n, shape);
    if (const std::string problem = viewBoundsProblem(b, dim); !problem.empty()) fail("view.bounds", problem);
    view.bounds = std::move(b);
  }
  if (const json* x = find(v, "projection"))
    view.projection = choice<Projection>(
        *x, "view.projection",
        {{"perspective", Projection::Perspective}, {"orthographic", Projection::Orthographic}});
  if (const json* x = find(v, "camera")) view.camera = readCamera(*x, "view.camera");
  if (const json* x = find(v, "view2d")) {
    object(*x, "view.view2d", {"center", "half_height"});
    if (const json* c = find(*x, "center")) view.center2d = fixed<2>(*c, "view.view2d.center", "[x, y]");
    if (const json* h = find(*x, "half_height")) view.halfHeight2d = positive(*h, "view.view2d.half_height");
  }
  if (const json* x = find(v, "show_points")) view.showPoints = boolean(*x, "view.show_points");
  if (const json* x = find(v, "show_normals")) view.showNormals = boolean(*x, "view.show_normals");
  if (const json* x = find(v, "show_bounds")) view.showBounds = boolean(*x, "view.show_bounds");
  if (const json* x = find(v, "trace"))
    view.trace = choice<TraceMode>(
        *x, "view.trace", {{"auto", TraceMode::Auto}, {"baked", TraceMode::Baked}, {"exact", TraceMode::Exact}});
  if (const json* x = find(v, "slice")) view.slice = readSlice(*x, "view.slice");
  return view;
}

Vec<3> SceneReader::vec3(const json& v, const std::string& path) const {
  const auto a = fixed<3>(v, path, "[x, y, z]");
  return Vec<3>(a[0], a[1], a[2]);
}

PatchSpec SceneReader::readPatch(const json& v) const {
  object(v, "patch", {"preset", "splits", "domain", "form", "show_error", "show_iso_lines", "show_handles",
                      "tessellation", "knots"});
  PatchSpec p;
  if (const json* x = find(v, "preset")) {
    p.preset = string(*x, "patch.preset");
    bool known = false;
    std::string names;
    for (const auto& [n, _] : patchPresets()) {
      known |= n == p.preset;
      names += (names.empty() ? "" : ", ") + n;
    }
    if (!known) fail("patch.preset", "unknown preset '" + p.preset + "' (expected one of: " + names + ")");
  }
  if (const json* x = find(v, "splits")) {
    if (!x->is_array() || x->size() != 2) fail("patch.splits", "must be [n, m] (got " + describe(*x) + ")");
    p.splits = {integer((*x)[0], "patch.splits[0]", 1, 16), integer((*x)[1], "patch.splits[1]", 1, 16)};
  }
  if (const json* x = find(v, "domain")) {
    p.domain = fixed<4>(*x, "patch.domain", "[U0, U1, V0, V1]");
    if (!(p.domain[0] < p.domain[1]) || !(p.domain[2] < p.domain[3]))
      fail("patch.domain", "must satisfy U0 < U1 and V0 < V1");
  }
  if (const json* x = find(v, "form"))
    p.form = choice<PatchForm>(*x, "patch.form", {{"hermite", PatchForm::Hermite}, {"bezier", PatchForm::Bezier}});
  if (const json* x = find(v, "show_error")) p.showError = boolean(*x, "patch.show_error");
  if (const json* x = find(v, "show_iso_lines")) p.showIsoLines = boolean(*x, "patch.show_iso_lines");
  if (const json* x = find(v, "show_handles")) p.showHandles = boolean(*x, "patch.show_handles");
  if (const json* x = find(v, "tessellation")) p.tessellation = integer(*x, "patch.tessellation", 2, 256);
  if (const json* x = find(v, "knots")) {
    if (!x->is_array()) fail("patch.knots", "must be an array of {X, Xu, Xv, Xuv} (got " + describe(*x) + ")");
    const std::size_t want = std::size_t(p.splits[0] + 1) * std::size_t(p.splits[1] + 1);
    if (x->size() != want)
      fail("patch.knots", "must have (splits[0] + 1) × (splits[1] + 1) = " + std::to_string(want) + " entries (got " +
                              std::to_string(x->size()) + ")");
    for (std::size_t k = 0; k < x->size(); ++k) {
      const std::string path = indexPath("patch.knots", k);
      const json& e = (*x)[k];
      object(e, path, {"X", "Xu", "Xv", "Xuv"});
      KnotData d;
      for (const auto& [key, target] : {std::pair{"X", &d.X}, std::pair{"Xu", &d.Xu}, std::pair{"Xv", &d.Xv},
                                        std::pair{"Xuv", &d.Xuv}}) {
        const json* c = find(e, key);
        if (!c) fail(childPath(path, key), "missing (each knot has X, Xu, Xv and Xuv)");
        *target = vec3(*c, childPath(path, key));
      }
      p.knots.push_back(d);
    }
  }
  return p;
}

HoleFillSpec SceneReader::readHoleFill(const json& v) const {
  object(v, "holefill", {"mesh", "preset", "stage", "implicit", "rings"});
  HoleFillSpec h;
  if (const json* x = find(v, "mesh")) {
    h.mesh = string(*x, "holefill.mesh");
    if (h.mesh.empty()) fail("holefill.mesh", "must be a file name (or leave the key out for the preset)");
    const std::filesystem::path p(h.mesh);
    h.resolvedMesh = p.is_absolute() || baseDirectory_.empty() ? h.mesh : (std::filesystem::path(baseDirectory_) / p).string();
  }
  if (const json* x = find(v, "preset")) {
    h.preset = string(*x, "holefill.preset");
    bool known = false;
    std::string names;
    for (const auto& [n, _] : holeFillPresets()) {
      known |= n == h.preset;
      names += (names.empty() ? "" : ", ") + n;
    }
    if (!known) fail("holefill.preset", "unknown preset '" + h.preset + "' (expected one of: " + names + ")");
  }
  if (const json* x = find(v, "stage"))
    h.stage = choice<HoleFillStage>(*x, "holefill.stage",
                                    {{"holes", HoleFillStage::Holes}, {"front", HoleFillStage::Front},
                                     {"fair", HoleFillStage::Fair}, {"fit", HoleFillStage::Fit},
                                     {"project", HoleFillStage::Project}});
  if (const json* x = find(v, "implicit"))
    h.implicit = choice<HoleImplicitKind>(*x, "holefill.implicit",
                                          {{"rbf-offset", HoleImplicitKind::RbfOffset}, {"hrbf", HoleImplicitKind::Hrbf}});
  if (const json* x = find(v, "rings")) h.rings = integer(*x, "holefill.rings", 1, 10);
  return h;
}

Scene SceneReader::read(const json& document) const {
  object(document, "", {"version", "mode", "data", "fit", "transform", "view", "patch", "holefill"});
  Scene scene;
  scene.sourceName = source_;

  const json* version = find(document, "version");
  if (!version) fail("version", "missing (required; this program reads scene version 1)");
  scene.version = integer(*version, "version", INT_MIN, INT_MAX);
  if (scene.version != 1)
    fail("version", "unsupported scene version " + std::to_string(scene.version) +
                        " (this program reads version 1)");

  const json* mode = find(document, "mode");
  if (!mode) fail("mode", "missing (required; one of: implicit2d, implicit3d, patch, holefill)");
  scene.mode = readMode(*mode);
  const int dim = scene.dimension();

  const json* data = find(document, "data");
  if (data) {
    scene.data = readData(*data, dim);
  } else if (scene.mode == SceneMode::Patch || scene.mode == SceneMode::HoleFill) {
    scene.data.preset = "sphere6";  // unused by the patch editor and hole filling
  } else {
    fail("data", "missing (required: {\"preset\": NAME}, {\"file\": PATH} or "
                 "{\"points\": [...], \"normals\": [...]})");
  }
  if (const json* x = find(document, "patch")) scene.patch = readPatch(*x);
  if (const json* x = find(document, "holefill")) scene.holefill = readHoleFill(*x);

  if (const json* x = find(document, "fit")) scene.fit = readFit(*x);
  if (const json* x = find(document, "transform")) scene.transform = readTransform(*x, dim);
  else scene.transform.translate.assign(static_cast<std::size_t>(dim), 0.0);
  if (const json* x = find(document, "view")) scene.view = readView(*x, dim);
  return scene;
}

template <std::size_t N>
json toArray(const std::array<double, N>& a) {
  json out = json::array();
  for (double v : a) out.push_back(v);
  return out;
}

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
      throw InputError("--set " + key + ": " + path + " is not an object (it is " + describe(child) +
                       "), so it cannot hold '" + parts[i + 1] + "'");
    node = &child;
  }
  (*node)[parts.back()] = std::move(value);
}

Scene parseScene(const json& document, const std::string& sourceName, const std::string& baseDirectory) {
  return SceneReader(sourceName, baseDirectory).read(document);
}

Scene loadSceneFile(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": cannot open (it is a directory)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
  const std::string text = buffer.str();

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
          for (const std::string& part : keyPath) full = childPath(full, part);
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
  }
  for (const std::string& o : overrides) applySetOverride(document, o);
  const std::string base = std::filesystem::path(path).parent_path().string();
  return parseScene(document, path, base);
}

json sceneToJson(const Scene& scene) {
  const int dim = scene.dimension();
  json doc = json::object();
  doc["version"] = scene.version;
  doc["mode"] = std::string(sceneModeName(scene.mode));

  json data = json::object();
  if (!scene.data.preset.empty()) {
    data["preset"] = scene.data.preset;
    data["count"] = scene.data.count;
  } else if (!scene.data.file.empty()) {
    data["file"] = scene.data.file;
  } else {
    data["points"] = scene.data.points;
    data["normals"] = scene.data.normals;
  }
  doc["data"] = std::move(data);

  const FitSpec& f = scene.fit;
  doc["fit"] = {{"method", std::string(fitMethodName(f.method))},
                {"kernel", std::string(kernelName(f.kernel))},
                {"radius", f.radius},
                {"polynomial", std::string(polynomialName(f.polynomial))},
                {"smoothing", f.smoothing},
                {"shift", f.shift},
                {"solver", std::string(solverName(f.solver))},
                {"partition",
                 {{"enabled", f.partition.enabled},
                  {"max_points_per_box", f.partition.maxPointsPerBox},
                  {"box_size", f.partition.boxSize},
                  {"overlap", f.partition.overlap},
                  {"blend", std::string(puBlendName(f.partition.blend))}}}};

  const TransformSpec& t = scene.transform;
  json translate = json::array();
  for (int i = 0; i < dim; ++i)
    translate.push_back(static_cast<std::size_t>(i) < t.translate.size() ? t.translate[static_cast<std::size_t>(i)] : 0.0);
  json transform = {{"translate", std::move(translate)}, {"scale", t.scale}};
  if (dim == 2) transform["rotate_deg"] = t.rotateDeg;
  else transform["rotate_axis_angle_deg"] = toArray(t.rotateAxisAngleDeg);
  transform["method"] = std::string(transformMethodName(t.method));
  if (!t.matrix.empty()) transform["matrix"] = t.matrix;
  if (t.verify) transform["verify"] = true;
  doc["transform"] = std::move(transform);

  const ViewSpec& v = scene.view;
  json view = json::object();
  view["size"] = {v.size[0], v.size[1]};
  view["background"] = toArray(v.background);
  view["bounds"] = v.bounds ? json(*v.bounds) : json(nullptr);
  view["projection"] = std::string(projectionName(v.projection));
  view["camera"] = {{"eye", toArray(v.camera.eye)},
                    {"target", toArray(v.camera.target)},
                    {"up", toArray(v.camera.up)},
                    {"fov_y_deg", v.camera.fovYDeg}};
  view["view2d"] = {{"center", toArray(v.center2d)}, {"half_height", v.halfHeight2d}};
  view["show_points"] = v.showPoints;
  view["show_normals"] = v.showNormals;
  view["show_bounds"] = v.showBounds;
  view["trace"] = std::string(traceModeName(v.trace));
  view["slice"] = {{"enabled", v.slice.enabled}, {"normal", toArray(v.slice.normal)}, {"offset", v.slice.offset}};
  doc["view"] = std::move(view);
  if (scene.mode == SceneMode::Patch) {
    const PatchSpec& p = scene.patch;
    const auto vec = [](const Vec<3>& x) { return json::array({x.x(), x.y(), x.z()}); };
    json patch = {{"preset", p.preset},
                  {"splits", {p.splits[0], p.splits[1]}},
                  {"domain", toArray(p.domain)},
                  {"form", std::string(patchFormName(p.form))},
                  {"show_error", p.showError},
                  {"show_iso_lines", p.showIsoLines},
                  {"show_handles", p.showHandles},
                  {"tessellation", p.tessellation}};
    if (!p.knots.empty()) {
      json knots = json::array();
      for (const KnotData& k : p.knots) knots.push_back({{"X", vec(k.X)}, {"Xu", vec(k.Xu)}, {"Xv", vec(k.Xv)}, {"Xuv", vec(k.Xuv)}});
      patch["knots"] = std::move(knots);
    }
    doc["patch"] = std::move(patch);
  }
  if (scene.mode == SceneMode::HoleFill) {
    const HoleFillSpec& h = scene.holefill;
    json hf = {{"preset", h.preset},
               {"stage", std::string(holeFillStageName(h.stage))},
               {"implicit", h.implicit == HoleImplicitKind::Hrbf ? "hrbf" : "rbf-offset"},
               {"rings", h.rings}};
    if (!h.mesh.empty()) hf["mesh"] = h.mesh;
    doc["holefill"] = std::move(hf);
  }
  return doc;
}

void saveSceneFile(const Scene& scene, const std::string& path) {
  writeFileAtomically(path, sceneToJson(scene).dump(2) + "\n");
}

}  // namespace hermite
