#pragma once
// The scene file (docs/scene-format.md): one JSON document drives the GUI, the CLI and the tests.
// Parsing is strict: an unknown key, a wrong type or an out-of-range value throws InputError
// whose message starts with the file name and names the key path ("fit.radius: must be > 0").
// Missing keys take the defaults written next to each field.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/pu/pu_tree.h"
#include "core/rbf/dense_solver.h"
#include "core/rbf/kernels.h"
#include "core/rbf/polynomial.h"
#include "core/trace/camera.h"
#include "core/base/enum_names.h"
#include "io/point_file.h"
#include "scene/hole_fill_stages.h"
#include "scene/patch_document.h"

namespace hermite {

enum class SceneMode { Implicit2d, Implicit3d, Patch, HoleFill };
enum class FitMethod { Hrbf, RbfOffset };
enum class TraceMode { Auto, Baked, Exact };

inline constexpr EnumName<SceneMode> kSceneModeNames[] = {{"implicit2d", SceneMode::Implicit2d},
                                                          {"implicit3d", SceneMode::Implicit3d},
                                                          {"patch", SceneMode::Patch},
                                                          {"holefill", SceneMode::HoleFill}};
inline constexpr EnumName<FitMethod> kFitMethodNames[] = {{"hrbf", FitMethod::Hrbf}, {"rbf-offset", FitMethod::RbfOffset}};
inline constexpr EnumName<Projection> kProjectionNames[] = {{"perspective", Projection::Perspective},
                                                            {"orthographic", Projection::Orthographic}};
inline constexpr EnumName<TraceMode> kTraceModeNames[] = {
    {"auto", TraceMode::Auto}, {"baked", TraceMode::Baked}, {"exact", TraceMode::Exact}};

// The 3D view's ground plane (render/ground_grid.h): none, or a grid under the data.
enum class Ground { Off, Grid };
inline constexpr EnumName<Ground> kGroundNames[] = {{"off", Ground::Off}, {"grid", Ground::Grid}};

std::string_view sceneModeName(SceneMode m);
std::string_view fitMethodName(FitMethod m);
std::string_view projectionName(Projection p);
std::string_view traceModeName(TraceMode t);

struct DataSpec {
  // Exactly one source is set: preset, file, or inline points/normals.
  std::string preset;             // e.g. "sphere6"; empty when not a preset
  int count = 0;                  // 0 = the preset's own count
  std::string file;               // as written in the scene
  std::string resolvedFile;       // file resolved against the scene file's directory
  std::vector<std::vector<double>> points;   // inline data, each of the scene's dimension
  std::vector<std::vector<double>> normals;  // inline data, same count as points
  GivenNormals orientNormals = GivenNormals::Auto;  // data.orient_normals: a file's normals re-oriented?
  bool isInline() const { return preset.empty() && file.empty(); }
  bool operator==(const DataSpec&) const = default;
};

// A key that reads "auto", true or false.
enum class AutoSwitch { Auto, On, Off };

// fit.partition.enabled: "auto" (dense while the global fit is small, else partition of unity;
// docs/scene-format.md, choosePartition in scene_fit_memory.h), true or false.
using PartitionSwitch = AutoSwitch;

struct PartitionSpec {
  PartitionSwitch enabled = PartitionSwitch::Auto;
  int maxPointsPerBox = 20;  // ≥ 1
  double boxSize = 0.0;      // ≥ 0; 0 = only the point-count rule
  double overlap = 1.5;      // ≥ 1: support = box scaled about its centre
  PuBlend blend = PuBlend::Smooth;  // added key: smooth (Shepard, C² bumps) | hard (box cut-off: artefact demo)
  double dataReach = 3.0;  // added key, > 0: data within this many local spacings of a sample (pu_data_reach.h)
  bool operator==(const PartitionSpec&) const = default;
};

struct FitSpec {
  FitMethod method = FitMethod::Hrbf;
  KernelType kernel = KernelType::Cubic;
  double radius = 1.0;                        // > 0 (accepted and ignored by cubic/polyharmonic)
  Polynomial polynomial = Polynomial::Linear;
  double smoothing = 0.0;                     // ≥ 0
  double shift = 0.01;                        // > 0, RBF-offset δ
  SolverChoice solver = SolverChoice::Auto;   // added key: auto | cholesky | nullspace-cholesky | ldlt | lu
  PartitionSpec partition;
  // Added key `reach_mask`: whether a global fit has no data beyond partition.dataReach local
  // spacings of every sample, as the partition of unity has (scene/data_reach_mask.h); "auto":
  // for data files of at least 50 samples.
  AutoSwitch reachMask = AutoSwitch::Auto;
  bool operator==(const FitSpec&) const = default;
};

// Which model a transformed similarity fit uses: auto = the coefficient update where it is the
// re-solved interpolant (docs/maths.md, Transforms), else the re-solve; update / re-solve force one
// (the GUI's switch, to compare them live).
enum class TransformMethod { Auto, Update, Resolve };
inline constexpr EnumName<TransformMethod> kTransformMethodNames[] = {
    {"auto", TransformMethod::Auto}, {"update", TransformMethod::Update}, {"re-solve", TransformMethod::Resolve}};
std::string_view transformMethodName(TransformMethod m);

struct TransformSpec {
  std::vector<double> translate;                     // 3 numbers (3D) or 2 (2D); default zeros
  std::array<double, 4> rotateAxisAngleDeg{0, 0, 1, 0};  // 3D: axis (non-zero) + degrees
  double rotateDeg = 0.0;                            // 2D: counter-clockwise degrees
  double scale = 1.0;                                // > 0, uniform
  TransformMethod method = TransformMethod::Auto;    // added key `method`
  // Added key `matrix`: a general linear map M (Dim × Dim, row-major; empty = identity) applied
  // after scale·R: x ↦ M·scale·R·x + translate. A non-similarity M (non-uniform scale, shear)
  // makes the field the exact composition f(T⁻¹x), which is not the re-solved interpolant.
  std::vector<double> matrix;
  // Added key `verify`: also re-solve on the transformed data and compare the field used with
  // it on probes (fit --json's transform.resolve_ms, max_abs_df, max_grad_diff). Off by default:
  // the comparison costs a whole fit.
  bool verify = false;
  bool matrixIsIdentity() const;
  bool isIdentity() const;
  bool operator==(const TransformSpec&) const = default;
};

struct SliceSpec {
  bool enabled = false;
  std::array<double, 3> normal{0, 0, 1};  // non-zero
  double offset = 0.0;
  bool operator==(const SliceSpec&) const = default;
};

// `view.show_normals: "auto"` (the default) draws the normals of clouds of up to this many
// samples: beyond it they hide the surface.
inline constexpr int kAutoNormalsMaxSamples = 1000;

struct ViewSpec {
  std::array<int, 2> size{800, 600};           // pixels, each in [1, 16384]
  std::array<double, 3> background{1, 1, 1};   // each in [0, 1]
  std::optional<std::vector<double>> bounds;   // null, or 2·Dim numbers (min then max, min < max)
  Projection projection = Projection::Perspective;
  CameraSpec camera;
  std::array<double, 2> center2d{0, 0};        // view2d.center
  double halfHeight2d = 1.5;                   // view2d.half_height > 0
  bool showPoints = true;
  std::optional<bool> showNormals;             // true, false, or none = "auto" (kAutoNormalsMaxSamples)
  bool showBounds = false;
  bool showAxes = false;                       // the axes gizmo in the lower-left corner (3D, GUI)
  bool presenter = false;                      // GUI: start in presenter mode (panels hidden, a large caption)
  Ground ground = Ground::Off;                 // a grid under the data, across the camera's up (3D implicit views)
  TraceMode trace = TraceMode::Auto;
  SliceSpec slice;
  // Whether the normals of `samples` samples are drawn (show_normals, with "auto" decided here).
  bool normalsShown(int samples) const { return showNormals ? *showNormals : samples <= kAutoNormalsMaxSamples; }
  bool operator==(const ViewSpec&) const = default;
};

struct Scene {
  int version = 1;
  SceneMode mode = SceneMode::Implicit3d;
  DataSpec data;
  FitSpec fit;
  TransformSpec transform;
  ViewSpec view;
  PatchSpec patch;                     // mode "patch": the patch editor's document
  HoleFillSpec holefill;               // mode "holefill": the mesh and the stage shown
  std::string sourceName = "<scene>";  // file name used in messages
  int dimension() const { return mode == SceneMode::Implicit2d ? 2 : 3; }
  bool operator==(const Scene&) const = default;
};

// Applies one `--set KEY=VALUE` to a JSON document before parsing: KEY is a dotted path
// (intermediate objects are created), VALUE is parsed as JSON and taken as a string when it
// is not valid JSON. Throws UsageError when there is no '=' or the key is empty.
void applySetOverride(nlohmann::json& document, const std::string& keyEqualsValue);

// Strict parse of a scene document. `sourceName` prefixes messages; relative data files are
// resolved against `baseDirectory`.
Scene parseScene(const nlohmann::json& document, const std::string& sourceName,
                 const std::string& baseDirectory);

// Reads a scene file (JSON syntax errors name the line and column), applies the overrides in
// order, then parses strictly.
Scene loadSceneFile(const std::string& path, const std::vector<std::string>& overrides = {});
// The same for the bytes of that file held in memory (`text`); `path` names it and gives the
// folder relative paths are resolved against.
Scene parseSceneText(const std::string& text, const std::string& path, const std::vector<std::string>& overrides = {});

// The complete document with every key (defaults included); parseScene(sceneToJson(s)) == s.
nlohmann::json sceneToJson(const Scene& scene);

// Writes the scene to `path` without destroying an existing file on failure (temporary + rename),
// with data.file and holefill.mesh relative to the folder of `path` (withPathsRelativeTo).
void saveSceneFile(const Scene& scene, const std::string& path);

}  // namespace hermite
