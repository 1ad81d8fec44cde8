#include "scene/degenerate_check.h"

#include "core/mesh/flat_masked_field.h"
#include "scene/view_bounds.h"

namespace hermite {

template <int Dim>
void checkDegenerateField(const Scene& scene, SceneFit<Dim>& fit) {
  if (fit.data.size() == 0) return;
  const Box<Dim> box = viewBounds<Dim>(scene.view, fit.data.points);
  // A coarser grid than the r sweep's (24³ / 100 cells: a fifth of the evaluations): this runs
  // after every fit the GUI makes, and a fraction of the bounds needs no fine grid.
  DegenerateFieldOptions options;
  options.resolution = Dim == 2 ? 100 : 24;
  const DegenerateFieldReport report = detectDegenerateField<Dim>(fit.unmaskedField(), box, fit.data, options);
  fit.degenerateField = report;
  fit.masked.reset();
  if (!report.degenerate) return;
  fit.warnings.push_back(report.message());
  fit.masked = std::make_unique<FlatMaskedField<Dim>>(fit.unmaskedField(), report.scale);
}

template void checkDegenerateField<2>(const Scene&, SceneFit<2>&);
template void checkDegenerateField<3>(const Scene&, SceneFit<3>&);

}  // namespace hermite
