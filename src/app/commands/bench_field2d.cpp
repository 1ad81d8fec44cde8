#include "app/commands/bench_field2d.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/base/ms_since.h"
#include "core/rbf/hrbf.h"
#include "core/shapes/presets.h"
#include "render/field2d_view.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"

namespace hermite {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

using render::ContextOptions;
using render::Field2dView;
using render::Field2dViewOptions;
using render::OffscreenTarget;
using render::createContext;

Field2dBenchResult benchField2dRefitRedraw(const Field2dBenchOptions& o) {
  ContextOptions co;
  co.width = o.size;
  co.height = o.size;
  co.visible = false;
  co.vsync = false;
  const auto context = createContext(o.backend, co);
  const HermiteSamples<2> samples = makePreset2d("curve2d", o.points);
  HrbfOptions ho;
  ho.kernel = o.kernel;
  ho.polynomial = o.polynomial;
  const View2d view(Vec<2>(0, 0), 1.25, o.size, o.size);
  Field2dViewOptions vo;
  vo.gridScale = o.gridScale;
  Field2dView v;
  OffscreenTarget target(o.size, o.size, false);
  target.bind();

  std::vector<double> total, fit, eval, draw;
  for (int r = 0; r < std::max(1, o.repetitions) + 1; ++r) {  // the first round warms up
    const auto t0 = Clock::now();
    const HrbfModel<2> model = fitHrbf(samples, ho);
    const double tFit = msSince(t0);
    v.setField(model, view, vo, samples.points, samples.normals);
    const auto t1 = Clock::now();
    v.draw();
    context->present();  // glFinish
    const double tDraw = msSince(t1) + v.uploadMs();
    const double tTotal = msSince(t0);
    if (r == 0) continue;
    total.push_back(tTotal);
    fit.push_back(tFit);
    eval.push_back(v.evaluateMs());
    draw.push_back(tDraw);
  }
  const auto median = [](std::vector<double> x) {
    std::sort(x.begin(), x.end());
    return x[x.size() / 2];
  };
  Field2dBenchResult out;
  out.medianMs = median(total);
  out.fitMs = median(fit);
  out.evaluateMs = median(eval);
  out.drawMs = median(draw);
  out.options = o;
  return out;
}

}  // namespace hermite
