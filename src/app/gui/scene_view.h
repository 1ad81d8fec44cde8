#pragma once
// Draws a fitted scene's view into an image: the one path the window, the r-explorer
// thumbnails, the compare split view, `render` and `sweep` share. 2D: the field view (heat map,
// iso-lines, zero curve, samples). 3D: the implicit tracer (bake, trace, slice, overlays).
//
// The field comes from a FitOutcome (kept alive here while the tracer references it); the view
// settings (camera, slice, overlays, background) from the scene passed to render(), which may be
// newer than the fit: moving the camera redraws without refitting. Needs a current GL context.

#include <memory>
#include <optional>

#include "app/gui/fit_worker.h"
#include "app/gui/in_frame_bake.h"
#include "app/gui/refined_rows.h"
#include "app/gui/view_job_runner.h"
#include "core/trace/image.h"
#include "render/field2d_view.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"
#include "render/implicit_tracer.h"
#include "render/mesh_view.h"

namespace hermite::app {

enum class ViewQuality {
  Interactive,  // while dragging: coarse 3D bake (64³), no exact refinement; 2D f every 6 px
  Settled,      // the view at rest: 128³ bake + exact refinement of every hit; 2D f at every pixel
};

struct SceneViewResult {
  int width = 0, height = 0;  // the view's size in pixels
  ImageRgba8 image;           // its pixels (empty when gpuImage is set)
  // 3D only: per-pixel surface hits (depth = ray parameter, +inf where none), for picking.
  std::vector<float> depth;
  double ms = 0;            // whole render (bake when the field changed, trace, refinement)
  double colourRange = 0;   // 2D heat map / 3D slice plane: the colours cover ±range (0: none)
  double isoSpacing = 0;    // 2D heat map / 3D slice plane: f between iso-lines
  int refinedPixels = 0;    // 3D
  std::string traceMode;    // 3D: "baked", "baked + refined" or "exact"; patch / hole filling: "rasterised"
  // Set instead of `image` when the render was asked to stay on the GPU (2D): the colour texture
  // of the renderer's own target, GL rows bottom-up, valid until its next render.
  const render::Texture* gpuImage = nullptr;
  // Background renders (SceneViewRenderer::setBackground): nothing to show yet for this fit (its
  // bake runs) or for this settled view (its rows are traced over several frames); the image on
  // screen stays until one arrives.
  bool nothingYet = false;
  // The fit whose field the pixels show (background 3D renders: an older one until the new fit's
  // first bake is on the GPU); null with nothingYet.
  const FitOutcome* drawnFrom = nullptr;
};

class SceneViewRenderer {
 public:
  SceneViewRenderer() = default;
  ~SceneViewRenderer();
  SceneViewRenderer(const SceneViewRenderer&) = delete;
  SceneViewRenderer& operator=(const SceneViewRenderer&) = delete;

  // Renders `fit` with the view of `viewScene` at width × height pixels. Throws InputError for
  // a failed fit (nothing to draw) and EnvironmentError from GL.
  // keepOnGpu: a 2D view is drawn into a target kept here and not read back (result.gpuImage;
  // readGpuImage() when pixels are wanted) — the window's path, which saves a read-back and a
  // re-upload of the whole view per frame. 3D views are always read back (picking needs depth).
  SceneViewResult render(const std::shared_ptr<const FitOutcome>& fit, const Scene& viewScene, int width, int height,
                         ViewQuality quality, bool keepOnGpu = false);
  // The pixels of the last keepOnGpu render (row 0 = top). Throws InputError when there is none.
  ImageRgba8 readGpuImage() const;

  // The window's 3D path: with `on`, bakes and exact refinement (with the CPU tracing of pixels
  // the GPU left undecided) run on a worker thread, and render() returns at once with the best
  // image it has — the coarse bake first, the baked settled image, then the refined one when it
  // arrives (adoptFinished). Off (the default): render() does all of it before returning.
  void setBackground(bool on) { background_ = on; }
  // Applies finished background work on the GL thread (uploads a bake, draws a refined image);
  // true when something arrived or a settled view is being traced in bands, and the view is worth
  // drawing again (render() traces the next bands). Throws what the work threw.
  bool adoptFinished();
  // Background work for the last render still runs or waits to be adopted, or its settled view
  // is being traced in bands.
  bool pending() const { return background_ && (jobs_.busy() || tracing_ || uploading_); }
  // Background work waits for the GL thread: a finished job, slabs to upload, bands to trace,
  // refined rows to copy. A frame drawn now shows something new (frame_pacing.h).
  bool hasFrameWork() const;

  // 2D heat map range ±colourRange (0: max |f| over the view) — the View panel's setting.
  double colourRange = 0;

 private:
  std::shared_ptr<const FitOutcome> field_;  // what the tracer / field view reference
  std::unique_ptr<render::ImplicitTracer> tracer_;
  std::unique_ptr<render::Field2dView> view2d_;
  std::unique_ptr<render::MeshView> meshView_;
  std::unique_ptr<render::OffscreenTarget> target2d_;  // keepOnGpu renders, resized on demand
  void renderField2d(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<2>& f, const Scene& viewScene,
                     ViewQuality quality, bool keepOnGpu, SceneViewResult& out);
  void renderField3d(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f, const Scene& viewScene,
                     ViewQuality quality, SceneViewResult& out);
  // The rasterised modes' images (the mesh view).
  ImageRgba8 renderPatch(const PatchDisplay& patch, const Scene& viewScene, int width, int height);
  ImageRgba8 renderHoleFill(const HoleFillStages& stages, const Scene& viewScene, int width, int height);
  void renderField3dInBackground(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f,
                                 const Scene& viewScene, ViewQuality quality, SceneViewResult& out);
  void requestBake(const std::shared_ptr<const FitOutcome>& fit, const Box<3>& bounds,
                   const std::vector<double>& boundsKey, int resolution);
  void requestRefinement(std::shared_ptr<render::DeferredRefinement> job, const std::shared_ptr<const FitOutcome>& fit);
  bool continueUpload(double budgetMs);
  bool bakeInFrame(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f, const Box<3>& bounds,
                   const std::vector<double>& boundsKey, int resolution);
  InFrameBake inFrameBake_;
  int bakeResolution_ = 0;
  std::optional<std::vector<double>> bakedBounds_;

  // Background renders: what the worker does now, and the refined image of the last settled view.
  struct BakeRequest {
    const FitOutcome* fit = nullptr;
    std::vector<double> bounds;
    int resolution = 0;
    bool operator==(const BakeRequest&) const = default;
  };
  struct RefinedView {
    const FitOutcome* fit = nullptr;
    ViewSpec view;
    int width = 0, height = 0;
    bool operator==(const RefinedView&) const = default;
  };
  bool background_ = false;
  ViewJobRunner jobs_;
  std::optional<BakeRequest> baking_;        // the bake submitted last (until it is uploaded)
  std::optional<RefinedView> refining_;      // the view whose refinement was submitted last
  std::optional<RefinedView> refinedView_;   // the view `refined_` shows
  std::optional<RefinedView> tracing_;       // the settled view being traced in bands (one per frame)
  // A finished bake whose textures are copied to the GPU over several frames.
  struct Uploading {
    std::shared_ptr<const FitOutcome> fit;  // kept alive: the tracer will reference its field
    std::vector<double> boundsKey;
    int resolution = 0;
  };
  std::optional<Uploading> uploading_;
  double frameSpentMs_ = 0;  // wall clock of this frame's adoptFinished, taken from the trace budget
  SceneViewResult refined_;
  // The settled view whose exact refinement fills in row band by row band while it runs: its
  // baked image with the refined rows copied in so far (RefinedRows says which are new).
  struct Progressive {
    std::shared_ptr<render::DeferredRefinement> job;
    std::shared_ptr<const FitOutcome> fit;
    RefinedView view;
    SceneViewResult image;
    std::uint64_t id = 0;
    bool finished = false;  // the job returned: every row is published
  };
  std::optional<Progressive> progressive_;
  RefinedRows rows_;
  std::uint64_t refinements_ = 0;  // refinement jobs submitted (RefinedRows job numbers)
  // Copies the rows the running refinement published since the last call into progressive_'s
  // image (GL thread); true when some arrived.
  bool takeRefinedRows();
  // Brings the tracer's bake towards `fit` over `bounds` at `quality`'s resolution (in this frame
  // or through the worker); true when the tracer holds a bake of `fit` over `bounds`.
  bool prepareBake(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f, const Box<3>& bounds,
                   ViewQuality quality);
  // The refined image of `view`, or its refinement filling in, into `out`; false when neither.
  bool takeArrivedImage(const RefinedView& view, SceneViewResult& out) const;
  // This frame's part of the settled trace of `view`; true with the finished trace in `r` (and
  // `job` ready for the worker's refinement).
  bool traceSettledPart(const RefinedView& view, const Camera& camera, const render::TraceSettings& s,
                        render::DeferredRefinement& job, render::TraceResult& r);
  // No refinement fills in rows any more (the view, the bake or the image moved on).
  void dropProgressive() {
    progressive_.reset();
    rows_.clear();
  }
};

// A hidden offscreen context of the given size on a headless backend ("osmesa", "egl"),
// current on the calling thread (render, sweep).
std::unique_ptr<render::RenderContext> offscreenContext(const std::string& backend, int width, int height);

// The patch editor's lines: iso-parameter lines of every patch and, when handles are shown, the
// Hermite tangent / twist arrows or the Bézier control net (world-space segments + colours).
void patchLines(const PatchDisplay& patch, const PatchSpec& spec, std::vector<Vec<3>>& ends, std::vector<Vec<3>>& colors);

// The 3D camera of a scene's view at a given pixel size.
Camera sceneCamera(const Scene& scene, int width, int height);
// The 2D view of a scene at a given pixel size.
View2d sceneView2d(const Scene& scene, int width, int height);

}  // namespace hermite::app
