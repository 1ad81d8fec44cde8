#pragma once
// The GPU tracer of 3D implicits, with the slice plane and overlays (docs/design.md, Rendering;
// the marches' maths in docs/maths.md, Volume bake and sphere tracing).
//
// Baked mode (default, fast on llvmpipe): f is baked on the CPU over the bounds into an R32F 3D
// texture (core/trace/volume_bake.h); a fragment shader marches each pixel's ray (the same rays
// as Camera and the CPU reference) brick by brick: bricks whose samples all have one sign are
// skipped (the trilinear interpolant cannot vanish there), inside a brick it steps by
// max(|f|/L, ε) with L = 1.01 × the trilinear interpolant's own Lipschitz bound on that brick
// (‖(max|Δₖf|/hₖ)ₖ‖: what the shader samples; the field's bound from lipschitzBound is often far
// above the true ‖∇f‖ for global kernels and only shrinks steps), and refines the first sign
// change by bisection on the interpolant.
//
// Exact refinement (settled views, the default for headless renders): the GPU's ray parameters
// are read back and every hit pixel is refined against the TRUE field on the CPU, then shaded
// with the true ∇f exactly like core/trace/shading.h; misses next to a hit (the silhouette ring)
// are searched too. hit_refinement.h says how, and what it cannot recover.
//
// Exact mode (RadialSum models: HRBF and RBF-offset, every kernel and polynomial): the shader
// sums the model from an SSBO and sphere-traces with per-brick Lipschitz bounds of the field.
// Every step costs a sum over all centres, so it is slow on software renderers: it is meant for
// real GPUs and reference images.
//
// Slice plane {x : n·x = offset} (unit n): f on the plane inside the bounds as a heat map
// (core/trace/color_map.h), iso-lines and the zero curve, depth-composited with the surface (the
// nearer of the surface hit and the plane hit wins per pixel).
//
// Overlays (points, normals, bounds box) are drawn depth-tested against the traced depth, which
// the tracer writes consistently with Camera::projectionMatrix(near, far) for the tracer's
// depth range. Every GL call must happen on the thread whose context is current.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"
#include "core/points/hermite_samples.h"
#include "core/rbf/radial_sum.h"
#include "core/trace/camera.h"
#include "core/trace/image.h"
#include "core/trace/volume_bake.h"

namespace hermite::render {

enum class TracerMode {
  Baked,  // 3D texture of f (any ImplicitField<3>)
  Exact,  // per-pixel evaluation of a RadialSum<3> in the shader
};

// Arithmetic of the exact shader's sum. Auto picks double where float rounding of the
// cancelling terms could move the surface (ImplicitTracer::exactNeedsDouble), else float.
enum class ExactPrecision { Auto, Float, Double };

struct SliceSettings {
  bool enabled = false;
  std::array<double, 3> normal{0, 0, 1};  // normalised by the tracer (must be non-zero)
  double offset = 0.0;                    // plane n̂·x = offset, world units along n̂
  double range = 0.0;                     // heat-map range |f|; ≤ 0: max |f| on the plane (from the bake)
};

struct TraceSettings {
  TracerMode mode = TracerMode::Baked;
  bool refineExact = true;    // CPU refinement of hits against the true field (settled views)
  bool showSurface = true;    // false: only the slice plane / overlays (to see inside)
  bool showPoints = false;    // samples as 4 px points
  bool showNormals = false;   // normals as lines of 5 % of the bounds diagonal
  bool showBounds = false;    // the bounds box as lines
  bool showGround = false;    // the ground grid under the samples (ground_grid.h)
  std::array<double, 3> groundUp{0, 1, 0};  // the grid's plane is across this direction
  SliceSettings slice;
  std::array<double, 3> background{1, 1, 1};  // each in [0, 1]; misses get round(255·c) exactly
  // Baked mode without a slice plane: run the trace pass only on the tiles the tile pass did not
  // prove empty (tile_spans.h). The pixels are the same either way; false traces every pixel.
  bool skipEmptyTiles = true;
  double minStepCells = 0.1;  // ε of the shader's march, in bake cells (baked) or 1e-3·diagonal units (exact)
  ExactPrecision exactPrecision = ExactPrecision::Auto;
};

// A render's pixels and what tests and tools need besides them. Arrays are W·H, row 0 = top.
struct TraceResult {
  ImageRgba8 image;
  std::vector<std::uint8_t> hit;  // 1 where the surface is the visible hit (not the slice plane)
  std::vector<float> depth;       // ray parameter t of the surface hit (world units; +inf elsewhere)
  std::vector<float> normal;      // 3·W·H outward unit normals of surface hits (0 elsewhere)
  double traceMs = 0;             // GPU trace pass incl. glFinish
  double refineMs = 0;            // CPU exact refinement (0 when off)
  double overlayMs = 0;           // overlays + read-back
  int refinedPixels = 0;          // hit pixels refined against the true field
  int ringHits = 0;               // silhouette-ring pixels the refinement added
  int droppedHits = 0;            // baked hits the true field does not confirm (turned to misses)
  bool exactDouble = false;       // exact mode summed in double precision
  int cpuTracedPixels = 0;        // pixels the GPU march left undecided (steps or loop budget), traced on the CPU
  long long tracedPixels = 0;     // pixels the GPU trace pass ran on (baked mode skips empty tiles)
  double sliceRange = 0;          // the slice's heat map covers ±sliceRange (0: no slice plane)
  double sliceIsoSpacing = 0;     // f between the slice's iso-lines
  Vec<3> normalAt(int i, int j) const {
    const std::size_t p = std::size_t(j) * image.width + i;
    return Vec<3>(normal[3 * p], normal[3 * p + 1], normal[3 * p + 2]);
  }
};

struct TracerUploadOptions {
  int bakeResolution = 128;  // R samples per axis of the baked texture
  int brickCells = 8;        // cells per brick edge (16³ bricks at R = 128)
};

// The CPU half of an upload: the bake and every texture's texels, made without GL on any thread
// (the window bakes on a worker); ImplicitTracer::upload(TracerVolume, …) then only copies them
// to the GPU.
struct TracerVolume {
  std::shared_ptr<const VolumeBake> bake;
  std::vector<float> brickTexels;          // RGBA32F per bake brick (bake->bricks.count)
  std::vector<float> bakedBrickTexels;     // RGBA32F per brick of the baked march's own grid
  Eigen::Array3i bakedBrickCount = Eigen::Array3i::Zero();
  Vec<3> bakedBrickSize = Vec<3>::Zero();  // world units
  std::vector<std::uint8_t> normalTexels;  // RGBA8 per sample (baked_normals.h)
  double bakeMs = 0;                       // wall clock of all of the above
  // Mean nearest-neighbour distance of the overlay samples (the marks scale with it), when the
  // caller computed it off the GL thread; < 0: the upload computes it.
  double sampleSpacing = -1;
};

// Bakes `field` over `bounds` (core/trace/volume_bake.h) and makes the textures' texels. Polls
// `cancel` slab by slab and throws Cancelled when it is set.
TracerVolume prepareTracerVolume(const ImplicitField<3>& field, const Box<3>& bounds,
                                 const TracerUploadOptions& options = {}, const CancelToken* cancel = nullptr);

// A settled frame whose exact refinement runs off the GL thread, in three steps:
// ImplicitTracer::render(camera, settings, &job) returns the baked image at once (unrefined) and
// fills `job`; refineDeferred(job) refines and composites it on any thread; on the GL thread
// ImplicitTracer::finishDeferred(job) draws the overlays over it and reads it back. Or, for an
// image that fills in while the job runs, ImplicitTracer::finishDeferredRows(job, …) takes the rows
// refineDeferred has published so far (rowsDone).
struct DeferredRefinement {
  std::optional<Camera> camera;
  TraceSettings settings;
  Box<3> bounds;
  Eigen::Vector2d depthRange = Eigen::Vector2d::Zero();
  std::shared_ptr<const VolumeBake> bake;
  const ImplicitField<3>* field = nullptr;  // the uploaded field: must outlive the job
  std::vector<float> surfaceT;              // W·H, row 0 = top: the GPU's hits (readSurfaceHits)
  std::vector<int> undecided;               // pixels the GPU march left undecided
  // The trace pass's colour, plane colour (RGBA8) and window depth, GL rows bottom-up; refineDeferred
  // composites the refined surface into color and depth.
  std::vector<std::uint8_t> color, planeColor;
  std::vector<float> depth;
  TraceResult result;  // hit, depth and normal as read back; refined by refineDeferred
  bool refined = false;
  // Rows [0, *rowsDone) (row 0 = top) of color, depth and result are refined and composited:
  // refineDeferred stores it after each band (release), readers load it (acquire) and then read
  // only those rows while the job runs. Shared so that the job stays copyable.
  std::shared_ptr<std::atomic<int>> rowsDone = std::make_shared<std::atomic<int>>(0);
};

// The CPU step of a deferred refinement (any thread). Throws Cancelled when `cancel` is set
// (polled between bands of rows); the job is then unusable.
void refineDeferred(DeferredRefinement& job, const CancelToken* cancel = nullptr);

class ImplicitTracer {
 public:
  // Needs a current GL 4.5 context; compiles the shaders (EnvironmentError on failure).
  ImplicitTracer();
  ~ImplicitTracer();
  ImplicitTracer(const ImplicitTracer&) = delete;
  ImplicitTracer& operator=(const ImplicitTracer&) = delete;

  // Bakes `field` over `bounds` on the CPU and uploads the textures; keeps a reference to
  // `field` (it must outlive the tracer or the next upload) for exact refinement. When the
  // field is a RadialSum<3> (HRBF, RBF-offset) its coefficients go to an SSBO for exact mode.
  // `samples` (may be null) feed the point and normal overlays (copied).
  void upload(const ImplicitField<3>& field, const Box<3>& bounds, const HermiteSamples<3>* samples = nullptr,
              const TracerUploadOptions& options = {});
  // The GL half of an upload: `volume` (prepareTracerVolume of `field`) to the GPU.
  void upload(TracerVolume volume, const ImplicitField<3>& field, const HermiteSamples<3>* samples = nullptr);
  // The same over several calls (the window's frames; staged_volume_upload.h): beginUpload
  // creates the new textures, each continueUpload copies slabs of them until `budgetMs` went by
  // and returns true once the tracer has switched to them. Until then the tracer draws the
  // previous upload, which must stay alive, and `field` must outlive the tracer or the next
  // upload. upload() and beginUpload() abandon an upload in progress.
  void beginUpload(TracerVolume volume, const ImplicitField<3>& field, const HermiteSamples<3>* samples = nullptr);
  bool continueUpload(double budgetMs);
  bool uploading() const { return staged_ != nullptr; }

  // Draws into an own offscreen target of the camera's size and reads it back. Throws
  // InputError for exact mode without a RadialSum model, or before upload().
  // With `deferred` (baked mode with refineExact), the exact refinement is left to
  // refineDeferred: the result is the baked image, and `deferred` gets what refinement needs.
  TraceResult render(const Camera& camera, const TraceSettings& settings, DeferredRefinement* deferred = nullptr);
  // The same frame over several calls, for a caller that must return within a time budget (the
  // window's settled view at full size): beginFrame runs the tile pass (with `halfTilePass`, the
  // first half of its tile rows: the first traceRows then runs the rest, and returns at once when
  // its budget is finite); the first traceRows after the whole tile pass also reads it back and
  // draws the rectangles it found; each traceRows marches the rays of the next bands of rows until
  // `budgetMs` of wall clock went by (bands sized by the costliest row so far, at least 8 rows;
  // infinity: every row left) and returns true once every row is traced; finishFrame then does
  // what render() does after the trace pass and returns the same bytes. render(),
  // beginFrame(), upload() and finishDeferred() abandon a frame in progress (they reuse its target).
  void beginFrame(const Camera& camera, const TraceSettings& settings, bool halfTilePass = false);
  bool traceRows(double budgetMs);
  // Optional, after the last traceRows: the next of finishFrame's read-backs (the surface hits,
  // then the trace pass's colour, plane colour and depth), one per call, so that a caller with a
  // frame budget spreads them over frames; true once none is left. finishFrame does the rest.
  bool readBackStep();
  TraceResult finishFrame(DeferredRefinement* deferred = nullptr);
  // A frame was begun and is neither finished nor abandoned.
  bool frameStarted() const;
  // The refined image of a job that refineDeferred finished: its colour and depth into the
  // target, the overlays over them, read back. The tracer must hold the upload the job was made
  // from (the samples the overlays draw).
  TraceResult finishDeferred(DeferredRefinement& job);
  // Rows [rowBegin, rowEnd) (row 0 = top; within *job.rowsDone) of the job's refined image: their
  // colour and depth into the target, the overlays drawn over them under a scissor, their pixels
  // read back into those rows of `image` (width × height of the job's camera) and their surface
  // depth (TraceResult::depth) into `depth`; other rows are left as they are. Over rows covering
  // the frame, the image equals finishDeferred's byte for byte. Abandons a frame in progress.
  void finishDeferredRows(const DeferredRefinement& job, int rowBegin, int rowEnd, ImageRgba8& image,
                          std::vector<float>& depth);

  // True when exact mode is available (the uploaded field is a RadialSum<3>).
  bool hasExactModel() const;
  // True when float evaluation of the uploaded RadialSum could move its surface by more than
  // 1e-4 of the bounds diagonal: 2⁻²⁴·√N times the largest sum of term magnitudes
  // (RadialSum::termMagnitude) on a 6³ grid, read as a distance since fits have |∇f| ≈ 1 at the
  // data. RBF-offset dipoles and polyharmonic kernels typically need double.
  // Decided on first use after each upload (216·N kernel evaluations), not in upload itself:
  // baked-mode uploads (every 3D drag) never need it. False without a RadialSum.
  bool exactNeedsDouble() const;
  const VolumeBake& bake() const;
  double bakeMs() const { return bakeMs_; }      // CPU bake of the last upload (samples + bricks)
  double uploadMs() const { return uploadMs_; }  // texture / SSBO upload of the last upload
  // The [near, far] used for depth: Camera::depthRange of the bounds grown by 10 % of the diagonal.
  Eigen::Vector2d depthRange(const Camera& camera) const;

 private:
  struct Gpu;
  struct Frame;
  struct Staged;
  std::unique_ptr<Gpu> gpu_;
  std::unique_ptr<Frame> frame_;    // the frame beginFrame started
  std::unique_ptr<Staged> staged_;  // the upload beginUpload started
  void adoptStaged();
  const ImplicitField<3>* field_ = nullptr;
  const RadialSum<3>* radialSum_ = nullptr;
  mutable std::optional<bool> exactNeedsDouble_;  // cache of exactNeedsDouble(), reset by upload
  Box<3> bounds_;
  std::shared_ptr<const VolumeBake> bake_;
  HermiteSamples<3> samples_;
  bool hasSamples_ = false;
  double bakeMs_ = 0, uploadMs_ = 0;
};

}  // namespace hermite::render
