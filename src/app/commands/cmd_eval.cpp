// `hermite-lab eval SCENE --at FILE`: f and ∇f of the scene's (transformed) fit at each probe
// point, one line "f g1 g2 [g3]" per point, %.17g so the doubles round-trip.

#include <cstdio>
#include <string>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "app/gui/scene_loading.h"
#include "io/point_file.h"
#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

template <int Dim>
void evalScene(const Scene& scene, const std::string& probeFile) {
  Points<Dim> X;
  if constexpr (Dim == 2)
    X = loadProbePoints2d(probeFile);
  else
    X = loadProbePoints3d(probeFile);
  const SceneFit<Dim> fit = fitScene<Dim>(scene);
  Eigen::VectorXd f;
  Points<Dim> G;
  fit.field().evaluateBatch(X, f, &G);
  std::string out;
  out.reserve(static_cast<size_t>(X.cols()) * 25 * (Dim + 1));
  char buf[32];
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    for (int k = 0; k <= Dim; ++k) {
      const double v = k == 0 ? f(i) : G(k - 1, i);
      const int len = std::snprintf(buf, sizeof buf, "%.17g", v);
      out.append(buf, len);
      out.push_back(k == Dim ? '\n' : ' ');
    }
    if (out.size() > (1 << 20)) {
      writeStdout(out);
      out.clear();
    }
  }
  writeStdout(out);
}

}  // namespace

int runEval(const EvalArgs& args) {
  const Scene scene = loadCommandScene(args.scene);
  if (scene.dimension() == 2)
    evalScene<2>(scene, args.probeFile);
  else
    evalScene<3>(scene, args.probeFile);
  return 0;
}

}  // namespace hermite::app
