#include "scene/degenerate_check.h"

#include <algorithm>
#include <cmath>

#include "core/mesh/flat_masked_field.h"
#include "scene/view_bounds.h"

namespace hermite {

namespace {

// Grid cells along the longest side: 100 (2D) / 24 (3D), a fifth of the r sweep's evaluations —
// this runs after every fit the GUI makes and a fraction of the bounds needs no fine grid — and
// for a global fit of N samples at most about 4·10⁶ / N grid points (≥ 16 / 8 cells), so the
// check stays within tens of milliseconds and never holds up a cancel that arrives just after
// the fit (it is one uninterruptible batch evaluation).
template <int Dim>
int checkResolution(const SceneFit<Dim>& fit) {
  const int base = Dim == 2 ? 100 : 24, least = Dim == 2 ? 16 : 8;
  if (fit.pu()) return base;  // local evaluation: the cost per point does not grow with N
  const double points = 4e6 / double(std::max(1, fit.data.size()));
  const int cells = int(std::floor(Dim == 2 ? std::sqrt(points) : std::cbrt(points)));
  return std::clamp(cells, least, base);
}

}  // namespace

bool degenerateCheckApplies(KernelType kernel) { return Kernel{kernel, 1.0}.strictlyPositiveDefinite(); }

template <int Dim>
void checkDegenerateField(const Scene& scene, SceneFit<Dim>& fit) {
  fit.degenerateField.reset();
  fit.masked.reset();
  if (fit.data.size() == 0 || !degenerateCheckApplies(scene.fit.kernel)) return;
  const Box<Dim> box = viewBounds<Dim>(scene.view, fit.data.points);
  DegenerateFieldOptions options;
  options.resolution = checkResolution(fit);
  const DegenerateFieldReport report = detectDegenerateField<Dim>(fit.unmaskedField(), box, fit.data, options);
  fit.degenerateField = report;
  if (!report.degenerate) return;
  fit.warnings.push_back(report.message());
  fit.masked = std::make_unique<FlatMaskedField<Dim>>(fit.unmaskedField(), report.scale);
}

template void checkDegenerateField<2>(const Scene&, SceneFit<2>&);
template void checkDegenerateField<3>(const Scene&, SceneFit<3>&);

}  // namespace hermite
