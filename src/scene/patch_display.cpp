#include "scene/patch_display.h"

#include <chrono>
#include <cmath>

namespace hermite {

bool patchHasTorusReference(const PatchSpec& s) { return s.preset == "torus" || s.preset == "zero-twist"; }

PatchDisplay buildPatchDisplay(const PatchSpec& spec) {
  PatchDisplay v{buildPatchGrid(spec), {}, {}, 0, {}, 0};
  const auto t0 = std::chrono::steady_clock::now();
  const int S = spec.tessellation;
  v.mesh = v.grid.tessellate(S);
  v.tessellateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!patchHasTorusReference(spec)) return v;
  // Vertex (patch p = i·m + j, a, b) sits at s = a/(S−1), t = b/(S−1) of patch (i, j).
  const auto& u = v.grid.uKnots();
  const auto& w = v.grid.vKnots();
  const int m = v.grid.patchesV();
  v.vertexError.resize(std::size_t(v.mesh.positions.cols()));
  for (int p = 0; p < v.grid.patchesU() * m; ++p) {
    const int i = p / m, j = p % m;
    for (int a = 0; a < S; ++a)
      for (int b = 0; b < S; ++b) {
        const double uu = u[i] + (u[i + 1] - u[i]) * a / (S - 1), vv = w[j] + (w[j + 1] - w[j]) * b / (S - 1);
        const int k = p * S * S + a * S + b;
        const double e = (Vec<3>(v.mesh.positions.col(k)) - torusKnotData(uu, vv).X).norm();
        v.vertexError[std::size_t(k)] = e;
        v.maxError = std::max(v.maxError, e);
      }
  }
  if (spec.preset == "torus" && spec.knots.empty()) {
    PatchStudyOptions o;
    o.domain = spec.domain;
    o.splits = {{1, 1}};
    if (spec.splits != std::array<int, 2>{1, 1}) o.splits.push_back(spec.splits);
    v.table = torusPatchStudy(o);
  }
  return v;
}

}  // namespace hermite
