#include "app/gui/scene_view.h"

#include <chrono>
#include <cmath>

#include "app/gui/background_priority.h"
#include "app/gui/view_colours.h"
#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/points/hermite_samples.h"
#include "core/trace/shading.h"
#include "render/gl/offscreen.h"
#include "scene/view_bounds.h"

namespace hermite::app {

namespace {

// Wall clock per GUI frame for the trace pass of a settled 3D view (bands of rows): with the rest
// of a frame (ImGui, the view image, about 6–10 ms at 1280 × 800 on llvmpipe) it stays under 33 ms.
// The budget covers all the view's GL work of a frame: the slabs of an arriving bake's upload
// and the arrival of a refined image come first, the bands get what they left.
constexpr double kTraceBudgetMs = 12.0;
// Wall clock per GUI frame for copying an arrived bake's slabs to the GPU (a 128³ bake is 16 MB
// of texels: 23–32 ms in one piece on a loaded llvmpipe).
constexpr double kUploadBudgetMs = 6.0;

// This frame's share of a begun settled frame traced over several GUI frames (at full size the
// trace pass alone can take several frames' time on a software rasteriser; the image on screen
// stays meanwhile): the tile pass's second half, then bands of rows within `budgetMs`, then the
// read-backs one per frame (the 16 MB hit texture, its conversion, the trace pass). A step that
// used half the budget leaves the next one to the next frame. True when only finishFrame
// (overlays, the image's read-back) is left, which then gets a frame of its own.
bool traceSettledStep(render::ImplicitTracer& tracer, double budgetMs) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!tracer.traceRows(std::max(budgetMs - msSince(t0), 1.0)) || msSince(t0) > budgetMs / 2) return false;
  return tracer.readBackStep() && msSince(t0) <= budgetMs / 2;
}

}  // namespace

// A hidden context of the render's size on the named backend (osmesa, egl).
std::unique_ptr<render::RenderContext> offscreenContext(const std::string& backend, int width, int height) {
  render::ContextOptions co;
  co.width = width;
  co.height = height;
  co.visible = false;
  co.vsync = false;
  return render::createContext(backend, co);
}

SceneViewRenderer::~SceneViewRenderer() = default;

Camera sceneCamera(const Scene& scene, int width, int height) {
  return Camera(scene.view.camera, scene.view.projection, width, height, scene.view.halfHeight2d);
}

View2d sceneView2d(const Scene& scene, int width, int height) {
  return View2d(Vec<2>(scene.view.center2d[0], scene.view.center2d[1]), scene.view.halfHeight2d, width, height);
}

ImageRgba8 SceneViewRenderer::readGpuImage() const {
  if (!target2d_) throw InputError("no view drawn on the GPU yet");
  return target2d_->read();
}

SceneViewResult SceneViewRenderer::render(const std::shared_ptr<const FitOutcome>& fit, const Scene& viewScene,
                                          int width, int height, ViewQuality quality, bool keepOnGpu) {
  if (!fit || !fit->ok()) throw InputError("nothing to draw: " + (fit ? fit->error : std::string("no fit")));
  const auto t0 = std::chrono::steady_clock::now();
  SceneViewResult out;
  out.width = width;
  out.height = height;
  if (const auto* f2 = fit->as<SceneFit<2>>()) {
    renderField2d(fit, *f2, viewScene, quality, keepOnGpu, out);
  } else if (const auto* f3 = fit->as<SceneFit<3>>()) {
    renderField3d(fit, *f3, viewScene, quality, out);
  } else if (const auto* patch = fit->as<PatchDisplay>()) {
    out.image = renderPatch(*patch, viewScene, width, height);
    out.traceMode = "rasterised";
    field_ = fit;
  } else if (const auto* holefill = fit->as<HoleFillStages>()) {
    out.image = renderHoleFill(*holefill, viewScene, width, height);
    out.traceMode = "rasterised";
    field_ = fit;
  } else {
    throw InputError("nothing to draw: the fit has no model");
  }
  if (!out.nothingYet) out.drawnFrom = field_.get();
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

// The heat map, iso-lines, samples and normals of a 2D field, read back or kept on the GPU.
void SceneViewRenderer::renderField2d(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<2>& f,
                                      const Scene& viewScene, ViewQuality quality, bool keepOnGpu,
                                      SceneViewResult& out) {
  const ViewSpec& v = viewScene.view;
  const int width = out.width, height = out.height;
  if (!view2d_) view2d_ = std::make_unique<render::Field2dView>();
  render::Field2dViewOptions o;
  o.showPoints = v.showPoints;
  o.showNormals = v.normalsShown(f.data.size());
  o.bounds = viewBounds<2>(v, f.data.points);
  o.outsideColor = v.background;
  // While dragging: f and ∇f every 6 px, bilinear between, so a drag frame fits in one 60 Hz
  // frame (tests/render/test_field2d_view.cpp keeps the zero curve within a pixel at 1/8).
  o.gridScale = quality == ViewQuality::Interactive ? 1.0 / 6 : 1.0;
  o.style.range = colourRange;
  const View2d view = sceneView2d(viewScene, width, height);
  view2d_->setField(f.field(), view, o, f.data.points, f.data.normals);
  if (keepOnGpu) {
    if (!target2d_ || target2d_->width() != width || target2d_->height() != height)
      target2d_ = std::make_unique<render::OffscreenTarget>(width, height, false);
    target2d_->bind();
    view2d_->draw();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    out.gpuImage = &target2d_->framebuffer().color();
  } else {
    render::OffscreenTarget target(width, height, false);
    target.bind();
    view2d_->draw();
    out.image = target.read();
  }
  out.colourRange = view2d_->range();
  out.isoSpacing = view2d_->isoSpacing();
  field_ = fit;
}

namespace {

// The tracer's settings for a scene's view of a 3D fit at a quality.
render::TraceSettings traceSettings(const ViewSpec& v, const SceneFit<3>& f, ViewQuality quality, bool exactModel) {
  render::TraceSettings s;
  s.mode = v.trace == TraceMode::Exact && exactModel ? render::TracerMode::Exact : render::TracerMode::Baked;
  s.refineExact = quality == ViewQuality::Settled;
  s.showPoints = v.showPoints;
  s.showNormals = v.normalsShown(f.data.size());
  s.showBounds = v.showBounds;
  s.showGround = v.ground == Ground::Grid;
  s.groundUp = v.camera.up;
  s.slice.enabled = v.slice.enabled;
  s.slice.normal = v.slice.normal;
  s.slice.offset = v.slice.offset;
  s.background = v.background;
  return s;
}

std::vector<double> boxKey(const Box<3>& b) {
  return {b.lo.x(), b.lo.y(), b.lo.z(), b.hi.x(), b.hi.y(), b.hi.z()};
}

void takeTrace(render::TraceResult& r, SceneViewResult& out) {
  out.image = std::move(r.image);
  out.depth = std::move(r.depth);
  out.refinedPixels = r.refinedPixels;
  out.colourRange = r.sliceRange;  // the slice plane's heat map (0 without one)
  out.isoSpacing = r.sliceIsoSpacing;
}

}  // namespace

// A 3D field sphere-traced from its bake (re-baked when the field, the quality or the bounds
// changed), refined exactly when settled.
void SceneViewRenderer::renderField3d(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f,
                                      const Scene& viewScene, ViewQuality quality, SceneViewResult& out) {
  if (background_) return renderField3dInBackground(fit, f, viewScene, quality, out);
  const ViewSpec& v = viewScene.view;
  const int width = out.width, height = out.height;
  if (!tracer_) tracer_ = std::make_unique<render::ImplicitTracer>();
  const Box<3> bounds = viewBounds<3>(v, f.data.points);
  const int resolution = quality == ViewQuality::Interactive ? 64 : 128;
  const std::vector<double> boundsKey = boxKey(bounds);
  if (field_ != fit || bakeResolution_ != resolution || bakedBounds_ != boundsKey) {
    render::TracerUploadOptions uo;
    uo.bakeResolution = resolution;
    tracer_->upload(f.field(), bounds, &f.data, uo);
    field_ = fit;
    bakeResolution_ = resolution;
    bakedBounds_ = boundsKey;
  }
  const render::TraceSettings s = traceSettings(v, f, quality, tracer_->hasExactModel());
  render::TraceResult r = tracer_->render(sceneCamera(viewScene, width, height), s);
  takeTrace(r, out);
  out.traceMode = s.mode == render::TracerMode::Exact ? "exact" : s.refineExact ? "baked + refined" : "baked";
}

// The same without waiting. A fit without a bake yet keeps the image of the fit before it on
// screen (nothingYet; a gesture traces that fit's bake) while a 64³ bake runs; a settled view
// traces the bake it has (64³ until the 128³ one arrives) and, on the 128³ bake, leaves the
// exact refinement to the worker; the refined image replaces the baked one when it arrives,
// unless the view changed meanwhile (a gesture cancels its job).
void SceneViewRenderer::renderField3dInBackground(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f,
                                                  const Scene& viewScene, ViewQuality quality, SceneViewResult& out) {
  const ViewSpec& v = viewScene.view;
  if (!tracer_) tracer_ = std::make_unique<render::ImplicitTracer>();
  const bool baked = prepareBake(fit, f, viewBounds<3>(v, f.data.points), quality);
  // Without a gesture, tracing the previous fit's bake again would show nothing new (its surface
  // with the new fit's marks) at the price of a whole trace: the image on screen stays until the
  // new fit's bake arrives. A gesture still traces it, so that the camera follows the mouse.
  if (!field_ || (!baked && quality == ViewQuality::Settled)) {
    out.nothingYet = true;
    return;
  }
  const RefinedView view{fit.get(), v, out.width, out.height};
  if (baked && takeArrivedImage(view, out)) return;
  if (refining_ && !(*refining_ == view)) {  // the view moved on: its refinement is of no use
    jobs_.cancel();
    refining_.reset();
  }
  dropProgressive();
  render::TraceSettings s = traceSettings(v, f, quality, tracer_->hasExactModel());
  const bool refineNow = baked && quality == ViewQuality::Settled && bakeResolution_ >= 128;
  s.refineExact = refineNow;
  auto job = std::make_shared<render::DeferredRefinement>();
  const Camera camera = sceneCamera(viewScene, out.width, out.height);
  render::TraceResult r;
  if (quality == ViewQuality::Interactive) {  // half resolution: one frame
    tracing_.reset();
    r = tracer_->render(camera, s, job.get());
  } else if (!traceSettledPart(view, camera, s, *job, r)) {
    out.nothingYet = true;
    return;
  }
  takeTrace(r, out);
  out.traceMode = s.mode == render::TracerMode::Exact ? "exact" : "baked";
  // Other frames leave pixels the GPU left undecided as it drew them: a later frame replaces them.
  if (refineNow && job->camera && s.mode == render::TracerMode::Baked) {
    refining_ = view;
    // The baked image is shown now; the refinement's rows replace its rows as they arrive.
    progressive_ = Progressive{job, fit, view, out, ++refinements_};
    rows_.start(progressive_->id);
    requestRefinement(std::move(job), fit);
  }
}

// A drag's refit gets a coarse bake in this very frame when it is cheap, the worker's 64³ one
// later; otherwise the worker bakes 64³ first and the finer one when the view is settled.
bool SceneViewRenderer::prepareBake(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f,
                                    const Box<3>& bounds, ViewQuality quality) {
  const std::vector<double> boundsKey = boxKey(bounds);
  const int wanted = quality == ViewQuality::Interactive ? 64 : 128;
  bool baked = field_ == fit && bakedBounds_ == boundsKey;
  if (!baked && quality == ViewQuality::Interactive)
    if (const int r = inFrameBake_.resolutionFor(f.field()); r > 0) baked = bakeInFrame(fit, f, bounds, boundsKey, r);
  if (!baked) requestBake(fit, bounds, boundsKey, 64);
  else if (bakeResolution_ < wanted) requestBake(fit, bounds, boundsKey, wanted);
  return baked;
}

bool SceneViewRenderer::takeArrivedImage(const RefinedView& view, SceneViewResult& out) const {
  if (refinedView_ == view) {  // the refined image of this very view arrived
    out.image = refined_.image;
    out.depth = refined_.depth;
    out.refinedPixels = refined_.refinedPixels;
    out.colourRange = refined_.colourRange;
    out.isoSpacing = refined_.isoSpacing;
    out.traceMode = refined_.traceMode;
    return true;
  }
  if (progressive_ && progressive_->view == view) {  // its refinement fills in (takeRefinedRows)
    out = progressive_->image;
    return true;
  }
  return false;
}

bool SceneViewRenderer::traceSettledPart(const RefinedView& view, const Camera& camera,
                                         const render::TraceSettings& s, render::DeferredRefinement& job,
                                         render::TraceResult& r) {
  if (!(tracing_ == view) || !tracer_->frameStarted()) {
    tracing_ = view;
    // The frame begins with the first half of the tile pass, which the GL runs by the end of this
    // GUI frame; a GUI frame that already spent half the budget on arrivals (a bake's last slabs)
    // leaves it to the next one.
    if (frameSpentMs_ <= kTraceBudgetMs / 2) tracer_->beginFrame(camera, s, true);
    return false;
  }
  if (!traceSettledStep(*tracer_, std::max(kTraceBudgetMs - frameSpentMs_, 1.0))) return false;
  tracing_.reset();
  r = tracer_->finishFrame(&job);
  return true;
}

// The in-frame coarse bake of `fit`, uploaded at once; what the worker did for an older field
// (a bake running, one being uploaded, a refinement) is dropped: the newest fit wins.
bool SceneViewRenderer::bakeInFrame(const std::shared_ptr<const FitOutcome>& fit, const SceneFit<3>& f,
                                    const Box<3>& bounds, const std::vector<double>& boundsKey, int resolution) {
  jobs_.cancel();
  baking_.reset();
  refining_.reset();
  uploading_.reset();
  dropProgressive();
  tracer_->upload(inFrameBake_.bake(f.field(), bounds, resolution), f.field(), &f.data);
  field_ = fit;
  bakeResolution_ = resolution;
  bakedBounds_ = boundsKey;
  refinedView_.reset();
  tracing_.reset();
  return true;
}

void SceneViewRenderer::requestBake(const std::shared_ptr<const FitOutcome>& fit, const Box<3>& bounds,
                                    const std::vector<double>& boundsKey, int resolution) {
  const BakeRequest request{fit.get(), boundsKey, resolution};
  if (baking_ == request) return;  // already on its way
  // A coarse bake after a coarse bake (a drag's refits) lets the running one finish and show.
  const bool letRunningFinish = baking_ && baking_->resolution == 64 && resolution == 64;
  baking_ = request;
  refining_.reset();
  dropProgressive();
  jobs_.submit(
      [this, fit, bounds, boundsKey, resolution](const CancelToken& cancel) -> ViewJobRunner::Apply {
        lowerViewWorkerPriority();
        const SceneFit<3>& f = *fit->as<SceneFit<3>>();
        render::TracerUploadOptions uo;
        uo.bakeResolution = resolution;
        auto volume =
            std::make_shared<render::TracerVolume>(render::prepareTracerVolume(f.field(), bounds, uo, &cancel));
        volume->sampleSpacing = meanSampleSpacing<3>(f.data.points);  // here, not on the GL thread
        return [this, fit, volume, boundsKey, resolution] {
          const SceneFit<3>& g = *fit->as<SceneFit<3>>();
          // Copied over the next frames (continueUpload); the tracer draws the bake it has until then.
          tracer_->beginUpload(std::move(*volume), g.field(), &g.data);
          uploading_ = Uploading{fit, boundsKey, resolution};
        };
      },
      letRunningFinish);
}

void SceneViewRenderer::requestRefinement(std::shared_ptr<render::DeferredRefinement> job,
                                          const std::shared_ptr<const FitOutcome>& fit) {
  const std::uint64_t id = refinements_;
  jobs_.submit([this, job, fit, id](const CancelToken& cancel) -> ViewJobRunner::Apply {
    lowerViewWorkerPriority();
    render::refineDeferred(*job, &cancel);
    return [this, fit, id] {
      if (field_ != fit) return;  // another upload came first: the job's samples are gone
      if (!progressive_ || progressive_->id != id) return;  // a newer view superseded it
      progressive_->finished = true;
      takeRefinedRows();  // the rows not copied yet (all are published now); adopts the image
    };
  });
}

bool SceneViewRenderer::takeRefinedRows() {
  // A frame traced in bands uses the tracer's target, which finishDeferredRows would overwrite.
  if (!progressive_ || tracing_ || field_ != progressive_->fit) return false;
  Progressive& p = *progressive_;
  const int published = p.job->rowsDone->load(std::memory_order_acquire);
  const RowRange rows = rows_.take(p.id, published, p.view.height);
  if (!rows.empty()) tracer_->finishDeferredRows(*p.job, rows.begin, rows.end, p.image.image, p.image.depth);
  if (p.finished && rows_.complete(p.id, p.view.height)) {  // the refined image is whole
    refined_ = std::move(p.image);
    refined_.refinedPixels = p.job->result.refinedPixels;
    refined_.traceMode = p.job->settings.refineExact ? "baked + refined" : "baked";
    refinedView_ = p.view;
    refining_.reset();
    dropProgressive();
    return true;
  }
  return !rows.empty();
}

bool SceneViewRenderer::hasFrameWork() const {
  if (!background_) return false;
  if (jobs_.hasFinished() || tracing_ || uploading_) return true;
  return progressive_ && !progressive_->finished &&
         rows_.waiting(progressive_->id, progressive_->job->rowsDone->load(std::memory_order_acquire));
}

bool SceneViewRenderer::adoptFinished() {
  if (!background_) return false;
  const auto t0 = std::chrono::steady_clock::now();
  frameSpentMs_ = 0;
  bool arrived = false;
  if (ViewJobRunner::Apply apply = jobs_.takeFinished()) {
    apply();
    arrived = !uploading_;  // a refined image; a bake is worth drawing once it is on the GPU
  }
  if (uploading_) arrived = continueUpload(kUploadBudgetMs) || arrived;
  arrived = takeRefinedRows() || arrived;
  frameSpentMs_ = msSince(t0);
  return arrived || tracing_.has_value();
}

// The next slabs of the bake being uploaded; once all are on the GPU the tracer draws it.
bool SceneViewRenderer::continueUpload(double budgetMs) {
  try {
    if (!tracer_->continueUpload(budgetMs)) return false;
  } catch (...) {
    uploading_.reset();
    throw;
  }
  const Uploading u = std::move(*uploading_);
  uploading_.reset();
  field_ = u.fit;
  bakeResolution_ = u.resolution;
  bakedBounds_ = u.boundsKey;
  if (baking_ && baking_->fit == u.fit.get() && baking_->resolution == u.resolution) baking_.reset();
  refinedView_.reset();
  dropProgressive();
  tracing_.reset();  // the switch abandoned it
  return true;
}

void patchLines(const PatchDisplay& patch, const PatchSpec& spec, std::vector<Vec<3>>& ends, std::vector<Vec<3>>& colors) {
  const PatchGrid& g = patch.grid;
  if (spec.showIsoLines) {
    const Vec<3> iso(0.25, 0.22, 0.18);
    constexpr int kSegments = 24;
    for (int i = 0; i < g.patchesU(); ++i)
      for (int j = 0; j < g.patchesV(); ++j) {
        const HermitePatch& p = g.patch(i, j);
        for (int k = 0; k <= 4; ++k) {
          const double c = k / 4.0;
          for (int e = 0; e < kSegments; ++e) {
            const double a = double(e) / kSegments, b = double(e + 1) / kSegments;
            ends.push_back(p.evaluate(c, a).X);
            ends.push_back(p.evaluate(c, b).X);
            colors.push_back(iso);
            ends.push_back(p.evaluate(a, c).X);
            ends.push_back(p.evaluate(b, c).X);
            colors.push_back(iso);
          }
        }
      }
  }
  if (!spec.showHandles) return;
  const std::vector<KnotData> knots = patchKnotData(spec);
  if (spec.form == PatchForm::Hermite) {
    const Vec<3> red(0.85, 0.15, 0.1), green(0.1, 0.6, 0.15), blue(0.15, 0.3, 0.9);
    for (int a = 0; a <= spec.splits[0]; ++a)
      for (int b = 0; b <= spec.splits[1]; ++b) {
        const Vec<3> X = patchHandlePosition(spec, knots, {PatchHandle::Point, a, b, 0, 0});
        const Vec<3> tu = patchHandlePosition(spec, knots, {PatchHandle::TangentU, a, b, 0, 0});
        const Vec<3> tv = patchHandlePosition(spec, knots, {PatchHandle::TangentV, a, b, 0, 0});
        const Vec<3> tw = patchHandlePosition(spec, knots, {PatchHandle::Twist, a, b, 0, 0});
        for (const auto& [from, to, c] : {std::tuple{X, tu, red}, std::tuple{X, tv, green}, std::tuple{Vec<3>(tu + tv - X), tw, blue}}) {
          ends.push_back(from);
          ends.push_back(to);
          colors.push_back(c);
        }
      }
  } else {
    const Vec<3> net(0.45, 0.2, 0.6);
    for (int i = 0; i < g.patchesU(); ++i)
      for (int j = 0; j < g.patchesV(); ++j) {
        const auto c = patchControlPoints(spec, knots, i, j);
        for (int p = 0; p < 4; ++p)
          for (int q = 0; q < 4; ++q) {
            if (p < 3) {
              ends.push_back(c[p][q]);
              ends.push_back(c[p + 1][q]);
              colors.push_back(net);
            }
            if (q < 3) {
              ends.push_back(c[p][q]);
              ends.push_back(c[p][q + 1]);
              colors.push_back(net);
            }
          }
      }
  }
}

ImageRgba8 SceneViewRenderer::renderPatch(const PatchDisplay& patch, const Scene& viewScene, int width, int height) {
  if (!meshView_) meshView_ = std::make_unique<render::MeshView>();
  render::MeshDrawData d;
  d.positions = patch.mesh.positions;
  d.normals = patch.mesh.normals;
  d.triangles = patch.mesh.triangles;
  d.background = viewScene.view.background;
  const PatchSpec& spec = viewScene.patch;
  if (spec.showError && !patch.vertexError.empty() && patch.maxError > 0) {
    // The front colour towards red as the error grows (relative to the largest error).
    d.colors.resize(3, d.positions.cols());
    const Vec<3> front(shading::kFrontColor[0], shading::kFrontColor[1], shading::kFrontColor[2]),
        hot(kPatchErrorColour[0], kPatchErrorColour[1], kPatchErrorColour[2]);
    for (Eigen::Index k = 0; k < d.positions.cols(); ++k) {
      const double t = patch.vertexError[std::size_t(k)] / patch.maxError;
      d.colors.col(k) = (1 - t) * front + t * hot;
    }
  }
  patchLines(patch, spec, d.lineEnds, d.lineColors);
  return meshView_->render(sceneCamera(viewScene, width, height), d);
}

ImageRgba8 SceneViewRenderer::renderHoleFill(const HoleFillStages& st, const Scene& viewScene, int width,
                                                  int height) {
  if (!meshView_) meshView_ = std::make_unique<render::MeshView>();
  // The input in the front colour, each patch (own vertices, so it takes its own colour) in teal;
  // hole boundaries red, ring samples of the implicit as short green normals.
  const TriMesh& in = st.input;
  const Vec<3> front(shading::kFrontColor[0], shading::kFrontColor[1], shading::kFrontColor[2]),
      patchColour(kHolePatchColour[0], kHolePatchColour[1], kHolePatchColour[2]);
  int patchVertices = 0, patchTriangles = 0;
  for (const auto& h : st.holes) {
    patchVertices += 3 * int(h.patch.triangles.cols());
    patchTriangles += int(h.patch.triangles.cols());
  }
  const int V = in.vertexCount(), T = in.triangleCount();
  render::MeshDrawData d;
  d.positions.resize(3, V + patchVertices);
  d.normals.resize(3, V + patchVertices);
  d.colors.resize(3, V + patchVertices);
  d.triangles.resize(3, T + patchTriangles);
  d.positions.leftCols(V) = in.vertices;
  d.normals.leftCols(V) = vertexNormals(in);
  d.colors.leftCols(V).colwise() = front;
  d.triangles.leftCols(T) = in.triangles;
  int v = V, t = T;
  for (const auto& h : st.holes) {
    const HolePatch& p = h.patch;
    const auto at = [&](int id) -> Vec<3> { return id >= p.baseId ? Vec<3>(p.vertices.col(id - p.baseId)) : Vec<3>(in.vertices.col(id)); };
    for (Eigen::Index k = 0; k < p.triangles.cols(); ++k) {
      const Vec<3> a = at(p.triangles(0, k)), b = at(p.triangles(1, k)), c = at(p.triangles(2, k));
      const Vec<3> n = (b - a).cross(c - a).normalized();
      for (const Vec<3>& x : {a, b, c}) {
        d.positions.col(v) = x;
        d.normals.col(v) = n;
        d.colors.col(v) = patchColour;
        ++v;
      }
      d.triangles.col(t++) << v - 3, v - 2, v - 1;
    }
  }
  const Box<3> box = in.vertexCount() > 0 ? boundingBox<3>(in.vertices) : Box<3>{};
  const double diag = box.extent().norm();
  for (const auto& h : st.holes) {
    for (std::size_t k = 0; k < h.loop.size(); ++k) {
      d.lineEnds.push_back(in.vertices.col(h.loop[k]));
      d.lineEnds.push_back(in.vertices.col(h.loop[(k + 1) % h.loop.size()]));
      d.lineColors.emplace_back(kHoleRimColour[0], kHoleRimColour[1], kHoleRimColour[2]);
    }
    for (Eigen::Index k = 0; k < h.ringPoints.cols(); ++k) {
      d.lineEnds.push_back(h.ringPoints.col(k));
      d.lineEnds.push_back(h.ringPoints.col(k) + 0.02 * diag * h.ringNormals.col(k));
      d.lineColors.emplace_back(kRingNormalColour[0], kRingNormalColour[1], kRingNormalColour[2]);
    }
  }
  d.background = viewScene.view.background;
  return meshView_->render(sceneCamera(viewScene, width, height), d);
}

}  // namespace hermite::app
