// `hermite-lab eval SCENE --at FILE`: f and ∇f of the scene's (transformed) fit at each probe
// point, one line "f g1 g2 [g3]" per point, %.17g so the doubles round-trip.

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "app/commands/terminal_progress.h"
#include "app/gui/scene_loading.h"
#include "core/base/errors.h"
#include "io/point_file.h"
#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

// NumericalError (exit 3, nothing printed) when f or ∇f is not finite at a probe, naming the
// first such probe: printing "nan" with exit 0 would pass for a result.
template <int Dim>
void requireFiniteResults(const Points<Dim>& X, const Eigen::VectorXd& f, const Points<Dim>& G,
                          const std::string& probeFile) {
  Eigen::Index bad = -1, count = 0;
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    if (std::isfinite(f(i)) && G.col(i).allFinite()) continue;
    if (bad < 0) bad = i;
    ++count;
  }
  if (bad < 0) return;
  std::string at;
  char buf[32];
  for (int k = 0; k < Dim; ++k) {
    std::snprintf(buf, sizeof buf, "%.6g", X(k, bad));
    at += (k ? ", " : "") + std::string(buf);
  }
  throw NumericalError("eval: f or its gradient is not finite at " + std::to_string(count) + " of " +
                       std::to_string(X.cols()) + " probes of " + probeFile + " (first: probe " +
                       std::to_string(bad + 1) + " at (" + at + ")); the values overflow there");
}

template <int Dim>
void evalScene(const Scene& scene, const std::string& probeFile) {
  Points<Dim> X;
  if constexpr (Dim == 2)
    X = loadProbePoints2d(probeFile);
  else
    X = loadProbePoints3d(probeFile);
  std::optional<TerminalProgress> progress(std::in_place, "fitting " + scene.sourceName);
  const SceneFit<Dim> fit = fitScene<Dim>(scene);
  progress.reset();
  printDataWarnings(fit);
  Eigen::VectorXd f;
  Points<Dim> G;
  fit.field().evaluateBatch(X, f, &G);
  requireFiniteResults<Dim>(X, f, G, probeFile);
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
