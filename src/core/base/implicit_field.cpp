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

template <int Dim>
void ImplicitField<Dim>::validBatch(const Points<Dim>& X, std::vector<char>& out, double margin) const {
  const Eigen::Index n = X.cols();
  out.assign(static_cast<std::size_t>(n), 1);
  if (everywhereValid()) return;
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i)
    out[static_cast<std::size_t>(i)] = (margin > 0 ? validNear(X.col(i), margin) : valid(X.col(i))) ? 1 : 0;
}

template <int Dim>
void ImplicitField<Dim>::validOnZeroSetBatch(const Points<Dim>& X, std::vector<char>& out) const {
  const Eigen::Index n = X.cols();
  out.assign(static_cast<std::size_t>(n), 1);
  if (everywhereValid()) return;
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = validOnZeroSet(X.col(i)) ? 1 : 0;
}

template <int Dim>
void ImplicitField<Dim>::evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const {
  evaluateBatch(X, f);
  validBatch(X, valid);
}

template class ImplicitField<2>;
template class ImplicitField<3>;

}  // namespace hermite
