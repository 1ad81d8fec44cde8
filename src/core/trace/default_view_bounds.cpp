#include "core/trace/default_view_bounds.h"

#include "core/base/errors.h"

namespace hermite {

template <int Dim>
Box<Dim> defaultViewBounds(const Points<Dim>& samples) {
  if (samples.cols() < 1) throw InputError("view.bounds: no samples to derive default bounds from; set view.bounds");
  if (!samples.allFinite()) throw InputError("view.bounds: samples are not finite");
  Box<Dim> box = boundingBox<Dim>(samples);
  const double largest = box.extent().maxCoeff();
  const double margin = largest > 0 ? 0.25 * largest : 1.0;
  box.lo.array() -= margin;
  box.hi.array() += margin;
  return box;
}

template Box<2> defaultViewBounds<2>(const Points<2>&);
template Box<3> defaultViewBounds<3>(const Points<3>&);

}  // namespace hermite
