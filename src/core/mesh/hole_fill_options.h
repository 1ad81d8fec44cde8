#pragma once
// The settings of every hole-filling stage (hole_fill.h), with their defaults.

#include <functional>
#include <utility>
#include <vector>

namespace hermite {

enum class HoleImplicitKind { RbfOffset, Hrbf };

struct HoleFillOptions {
  // Advancing front: at most frontStepFactor · (n²/4 + 40n) + 10 steps for n boundary edges, then
  // the hole is reported as not closed (a bound, never a hang).
  double frontStepFactor = 1.0;
  // A new vertex closer than this × l to another front vertex is merged with it (the front splits).
  double mergeDistance = 1.0;
  int clipFrontSize = 6;  // fronts of at most this many vertices are closed by clipping (no new vertices)
  // fillHoles: when a front does not close, retry with these (mergeDistance, clipFrontSize) pairs
  // before reporting the hole (a front that wraps around a strongly curved part can fold).
  std::vector<std::pair<double, int>> frontRetries{{0.8, 8}, {0.6, 10}, {1.2, 4}};
  // Holes of more boundary edges than this skip the advancing front (its step bound grows as n²)
  // and go straight to the minimum-weight triangulation, which is also the fallback when every
  // front attempt fails.
  int frontMaxEdges = 200;
  bool fair = true;
  bool fitAndProject = true;          // stages 4–5 (off: the faired patch is the result)
  int rings = 2;                      // rings of vertices around the hole given to the fit (≥ 1)
  int maxFitSamples = 600;            // ring vertices beyond this are subsampled (dense solve)
  double offsetFraction = 0.05;       // d = this × hole diameter (RBF with offsets)
  HoleImplicitKind implicit = HoleImplicitKind::RbfOffset;
  int newtonIterations = 20;          // per vertex
  double newtonTolerance = 1e-7;      // step length below this × hole diameter: converged
  // Called with the fraction of the work done, in [0, 1] (fillHoles: of all holes, each weighted
  // by its boundary edges squared; fillHole: of that hole), from any thread, one call at a time,
  // from inside every stage except the dense fit and the fairing solve (so the gaps between calls
  // stay near those two steps' times); returning false cancels: the hole being filled stops at
  // once and the holes not yet started are skipped. Optional.
  std::function<bool(double)> progress;
};

}  // namespace hermite
