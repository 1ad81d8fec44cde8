#include "core/pu/reach_masked_field.h"

#include <algorithm>

#include "core/base/errors.h"

namespace hermite {

namespace {

// `points`, once the arguments are checked (before the tree is built on them).
template <int Dim>
const Points<Dim>& checkedPoints(const Points<Dim>& points, double reach, double vertexReach) {
  if (points.cols() < 1) throw InputError("data reach: no samples");
  if (!(reach > 0) || !(vertexReach > 0)) throw InputError("data reach: the reach factors must be > 0");
  return points;
}

}  // namespace

template <int Dim>
ReachMaskedField<Dim>::ReachMaskedField(const ImplicitField<Dim>& inner, const Points<Dim>& points, double reach,
                                        double vertexReach, std::unique_ptr<ImplicitField<Dim>> owned)
    : MaskedField<Dim>(inner, std::move(owned)),
      tree_(checkedPoints<Dim>(points, reach, vertexReach), PuTreeOptions{}),
      reach_(tree_, points, reach),
      zeroSetScale_(std::min(1.0, vertexReach / reach)) {}

template <int Dim>
bool ReachMaskedField<Dim>::validNear(const Vec<Dim>& x, double margin) const {
  if (!(margin > 0 ? this->inner().validNear(x, margin) : this->inner().valid(x))) return false;
  return reach_.reaches(tree_, x, margin);
}

template <int Dim>
bool ReachMaskedField<Dim>::validOnZeroSet(const Vec<Dim>& x) const {
  return this->inner().validOnZeroSet(x) && reach_.reaches(tree_, x, 0.0, zeroSetScale_);
}

template <int Dim>
void ReachMaskedField<Dim>::evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f,
                                               std::vector<char>& valid) const {
  this->inner().evaluateBatch(X, f);
  if (this->inner().everywhereValid()) valid.assign(std::size_t(X.cols()), 1);
  else this->inner().validBatch(X, valid);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < X.cols(); ++i)
    if (valid[std::size_t(i)] && !reach_.reaches(tree_, X.col(i))) valid[std::size_t(i)] = 0;
}

template class ReachMaskedField<2>;
template class ReachMaskedField<3>;

}  // namespace hermite
