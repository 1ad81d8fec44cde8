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

namespace {

// test(x) at the columns of X (Dim × N) into out (N entries, 1 = true), in parallel; all 1 for a
// field that is valid everywhere.
template <int Dim, class Test>
void markColumns(const ImplicitField<Dim>& field, const Points<Dim>& X, std::vector<char>& out, const Test& test) {
  const Eigen::Index n = X.cols();
  out.assign(static_cast<std::size_t>(n), 1);
  if (field.everywhereValid()) return;
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = test(X.col(i)) ? 1 : 0;
}

}  // namespace

template <int Dim>
void ImplicitField<Dim>::validBatch(const Points<Dim>& X, std::vector<char>& out, double margin) const {
  markColumns<Dim>(*this, X, out, [&](const auto& x) { return margin > 0 ? validNear(x, margin) : valid(x); });
}

template <int Dim>
void ImplicitField<Dim>::validOnZeroSetBatch(const Points<Dim>& X, std::vector<char>& out) const {
  markColumns<Dim>(*this, X, out, [&](const auto& x) { return validOnZeroSet(x); });
}

template <int Dim>
void ImplicitField<Dim>::evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const {
  evaluateBatch(X, f);
  validBatch(X, valid);
}

template class ImplicitField<2>;
template class ImplicitField<3>;

}  // namespace hermite
