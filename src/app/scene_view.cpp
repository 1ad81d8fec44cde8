#include "app/scene_view.h"

#include <chrono>
#include <cmath>

#include "core/errors.h"
#include "core/view_bounds.h"
#include "render/offscreen.h"

namespace hermite::app {

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

SceneViewResult SceneViewRenderer::render(const std::shared_ptr<const FitOutcome>& fit, const Scene& viewScene,
                                          int width, int height, ViewQuality quality) {
  if (!fit || !fit->ok()) throw InputError("nothing to draw: " + (fit ? fit->error : std::string("no fit")));
  const auto t0 = std::chrono::steady_clock::now();
  SceneViewResult out;
  const ViewSpec& v = viewScene.view;

  if (fit->fit2) {
    const SceneFit<2>& f = *fit->fit2;
    if (!view2d_) view2d_ = std::make_unique<render::Field2dView>();
    render::Field2dViewOptions o;
    o.showPoints = v.showPoints;
    o.showNormals = v.showNormals;
    o.bounds = viewBounds<2>(v, f.data.points);
    o.outsideColor = v.background;
    o.gridScale = quality == ViewQuality::Interactive ? 0.5 : 1.0;
    const View2d view = sceneView2d(viewScene, width, height);
    view2d_->setField(f.field(), view, o, f.data.points, f.data.normals);
    render::OffscreenTarget target(width, height, false);
    target.bind();
    view2d_->draw();
    out.image = target.read();
    out.colourRange = view2d_->range();
    out.isoSpacing = view2d_->isoSpacing();
    field_ = fit;
  } else if (fit->fit3) {
    const SceneFit<3>& f = *fit->fit3;
    if (!tracer_) tracer_ = std::make_unique<render::ImplicitTracer>();
    const Box<3> bounds = viewBounds<3>(v, f.data.points);
    const int resolution = quality == ViewQuality::Interactive ? 64 : 128;
    const std::vector<double> boundsKey{bounds.lo.x(), bounds.lo.y(), bounds.lo.z(),
                                        bounds.hi.x(), bounds.hi.y(), bounds.hi.z()};
    if (field_ != fit || bakeResolution_ != resolution || bakedBounds_ != boundsKey) {
      render::TracerUploadOptions uo;
      uo.bakeResolution = resolution;
      tracer_->upload(f.field(), bounds, &f.data, uo);
      field_ = fit;
      bakeResolution_ = resolution;
      bakedBounds_ = boundsKey;
    }
    render::TraceSettings s;
    const bool exact = v.trace == TraceMode::Exact && tracer_->hasExactModel();
    s.mode = exact ? render::TracerMode::Exact : render::TracerMode::Baked;
    s.refineExact = quality == ViewQuality::Settled;
    s.showPoints = v.showPoints;
    s.showNormals = v.showNormals;
    s.showBounds = v.showBounds;
    s.slice.enabled = v.slice.enabled;
    s.slice.normal = v.slice.normal;
    s.slice.offset = v.slice.offset;
    s.background = v.background;
    render::TraceResult r = tracer_->render(sceneCamera(viewScene, width, height), s);
    out.image = std::move(r.image);
    out.depth = std::move(r.depth);
    out.refinedPixels = r.refinedPixels;
    out.traceMode = exact ? "exact" : s.refineExact ? "baked + refined" : "baked";
  } else {
    throw InputError("nothing to draw: the fit has no model");
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace hermite::app
