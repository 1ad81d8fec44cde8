#include "core/base/implicit_field.h"

namespace hermite {

template <int Dim>
void ImplicitField<Dim>::evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) const {
  const Eigen::Index n = X.cols();
  f.resize(n);
  if (G) G->resize(Dim, n);
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    Vec<Dim> g;
    f(i) = evaluate(X.col(i), G ? &g : nullptr);
    if (G) G->col(i) = g;
  }
}

template class ImplicitField<2>;
template class ImplicitField<3>;

}  // namespace hermite
