#include "core/view_bounds.h"

#include <string>

#include "core/errors.h"

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

template <int Dim>
Box<Dim> viewBounds(const ViewSpec& view, const Points<Dim>& samples) {
  if (!view.bounds) return defaultViewBounds<Dim>(samples);
  const std::vector<double>& b = *view.bounds;
  if (b.size() != 2 * Dim)
    throw InputError("view.bounds: must have " + std::to_string(2 * Dim) + " numbers for a " + std::to_string(Dim) +
                     "D scene (got " + std::to_string(b.size()) + ")");
  Box<Dim> box;
  for (int k = 0; k < Dim; ++k) {
    box.lo(k) = b[k];
    box.hi(k) = b[Dim + k];
    if (!(std::isfinite(box.lo(k)) && std::isfinite(box.hi(k)) && box.lo(k) < box.hi(k)))
      throw InputError("view.bounds: min must be < max and both finite (axis " + std::to_string(k) + ")");
  }
  return box;
}

template Box<2> defaultViewBounds<2>(const Points<2>&);
template Box<3> defaultViewBounds<3>(const Points<3>&);
template Box<2> viewBounds<2>(const ViewSpec&, const Points<2>&);
template Box<3> viewBounds<3>(const ViewSpec&, const Points<3>&);

}  // namespace hermite
