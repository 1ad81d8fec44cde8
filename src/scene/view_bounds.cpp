#include "scene/view_bounds.h"

#include <cmath>
#include <string>

#include "core/base/errors.h"
#include "core/base/format_number.h"

namespace hermite {

std::string viewBoundsProblem(const std::vector<double>& bounds, int dim) {
  if (bounds.size() != 2 * static_cast<std::size_t>(dim))
    return "must have " + std::to_string(2 * dim) + " numbers for a " + std::to_string(dim) + "D scene (got " +
           std::to_string(bounds.size()) + ")";
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (int a = 0; a < dim; ++a) {
    const double lo = bounds[a], hi = bounds[a + dim];
    if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
      return std::string("min must be < max on every axis; on ") + kAxes[a] + " min is " + formatNumber(lo) +
             " and max is " + formatNumber(hi);
  }
  return "";
}

template <int Dim>
Box<Dim> viewBounds(const ViewSpec& view, const Points<Dim>& samples) {
  if (!view.bounds) return defaultViewBounds<Dim>(samples);
  const std::vector<double>& b = *view.bounds;
  if (const std::string problem = viewBoundsProblem(b, Dim); !problem.empty())
    throw InputError("view.bounds: " + problem);
  Box<Dim> box;
  for (int k = 0; k < Dim; ++k) {
    box.lo(k) = b[k];
    box.hi(k) = b[Dim + k];
  }
  return box;
}

template Box<2> viewBounds<2>(const ViewSpec&, const Points<2>&);
template Box<3> viewBounds<3>(const ViewSpec&, const Points<3>&);

}  // namespace hermite
