#include "core/patch/torus_patch_study.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <Eigen/SVD>

#include "core/base/errors.h"
#include "core/patch/bezier_patch.h"
#include "core/patch/patch_grid.h"

namespace hermite {

PlannedAllocation patchStudyPlan(int samples) {
  const std::uint64_t N = samples > 0 ? std::uint64_t(samples) : 0;
  return {saturatingProduct({4, N, N, sizeof(double)}), "the patch study with " + std::to_string(samples) + " x " +
                                                            std::to_string(samples) +
                                                            " samples per patch (4 matrices of that size)"};
}

std::vector<PatchStudyRow> torusPatchStudy(const PatchStudyOptions& o) {
  if (o.samples < 2) throw InputError("patch-table: --samples must be ≥ 2");
  checkMemory(patchStudyPlan(o.samples), "use fewer samples per patch (patch-table --samples)");
  const auto [U0, U1, V0, V1] = o.domain;
  if (!(U0 < U1) || !(V0 < V1) || !std::isfinite(U0 + U1 + V0 + V1))
    throw InputError("patch-table: --domain needs U0 < U1 and V0 < V1");
  std::vector<PatchStudyRow> rows;
  const int N = o.samples;
  for (const auto& split : o.splits) {
    const int n = split[0], m = split[1];
    if (n < 1 || m < 1) throw InputError("patch-table: splits must be ≥ 1");
    std::vector<double> uk(n + 1), vk(m + 1);
    for (int i = 0; i <= n; ++i) uk[i] = U0 + (U1 - U0) * i / n;
    for (int j = 0; j <= m; ++j) vk[j] = V0 + (V1 - V0) * j / m;
    const PatchGrid grid(uk, vk, torusKnotData);
    PatchStudyRow row{split, {0, 0, 0}, 0.0};
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const HermitePatch& hp = grid.patch(i, j);
        const BezierPatch bp = toBezier(hp);
        std::array<Eigen::MatrixXd, 3> E{Eigen::MatrixXd(N, N), Eigen::MatrixXd(N, N), Eigen::MatrixXd(N, N)};
        for (int a = 0; a < N; ++a)
          for (int b = 0; b < N; ++b) {
            const double s = double(a) / (N - 1), t = double(b) / (N - 1);
            const SurfacePoint h = hp.evaluate(s, t);
            const SurfacePoint z = bp.evaluate(s, t);
            const Vec<3> exact = torusKnotData(uk[i] + s * (uk[i + 1] - uk[i]), vk[j] + t * (vk[j + 1] - vk[j])).X;
            for (int k = 0; k < 3; ++k) E[k](a, b) = std::abs(h.X(k) - exact(k));
            row.hermiteBezierMaxDiff = std::max(row.hermiteBezierMaxDiff, (h.X - z.X).cwiseAbs().maxCoeff());
          }
        for (int k = 0; k < 3; ++k)
          row.error[k] += Eigen::JacobiSVD<Eigen::MatrixXd>(E[k]).singularValues()(0) / (n * m);
      }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace hermite
