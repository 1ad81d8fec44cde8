#include "core/mesh/flat_masked_field.h"

namespace hermite {

template <int Dim>
bool FlatMaskedField<Dim>::valid(const Vec<Dim>& x) const {
  return validNear(x, 0.0);
}

template <int Dim>
bool FlatMaskedField<Dim>::validNear(const Vec<Dim>& x, double margin) const {
  if (!(margin > 0 ? this->inner().validNear(x, margin) : this->inner().valid(x))) return false;
  Vec<Dim> g;
  const double f = this->inner().evaluate(x, &g);
  return !scale_.flat(f, g.norm());
}

template <int Dim>
void FlatMaskedField<Dim>::evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f,
                                              std::vector<char>& valid) const {
  Points<Dim> G;
  this->inner().evaluateBatch(X, f, &G);
  if (this->inner().everywhereValid()) valid.assign(std::size_t(X.cols()), 1);
  else this->inner().validBatch(X, valid);
  for (Eigen::Index i = 0; i < X.cols(); ++i)
    if (valid[std::size_t(i)] && scale_.flat(f(i), G.col(i).norm())) valid[std::size_t(i)] = 0;
}

template class FlatMaskedField<2>;
template class FlatMaskedField<3>;

}  // namespace hermite
