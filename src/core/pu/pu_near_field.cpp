#include "core/pu/pu_near_field.h"

#include <algorithm>
#include <limits>

namespace hermite {

template <int Dim>
double PuNearField<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  const double f = pu_.evaluate(x, g, H);
  if (!standIn(f)) return f;
  const int leaf = pu_.nearestSupport(x, reach_);
  return leaf < 0 ? f : pu_.leaves()[static_cast<std::size_t>(leaf)].model.evaluate(x, g, H);
}

template <int Dim>
void PuNearField<Dim>::evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) const {
  pu_.evaluateBatch(X, f, G);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    if (!standIn(f(i))) continue;
    const int leaf = pu_.nearestSupport(X.col(i), reach_);
    if (leaf < 0) continue;
    Vec<Dim> g;
    f(i) = pu_.leaves()[static_cast<std::size_t>(leaf)].model.evaluate(X.col(i), G ? &g : nullptr);
    if (G) G->col(i) = g;
  }
}

template <int Dim>
bool PuNearField<Dim>::validByExtension(const Vec<Dim>& x, double margin) const {
  if (!standIn(pu_.evaluate(x)) || pu_.nearestSupport(x, reach_) < 0) return false;
  const Vec<Dim> y = pu_.frame().applyInverse(x);
  return pu_.dataReach().reaches(pu_.tree(), y, margin / pu_.frame().q);
}

template <int Dim>
bool PuNearField<Dim>::validNear(const Vec<Dim>& x, double margin) const {
  // Where the blend has a value but no data reach, neither has the extension (the same reach).
  return pu_.validNear(x, margin) || validByExtension(x, margin);
}

template <int Dim>
void PuNearField<Dim>::validBatch(const Points<Dim>& X, std::vector<char>& out, double margin) const {
  pu_.validBatch(X, out, margin);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < X.cols(); ++i)
    if (!out[static_cast<std::size_t>(i)] && validByExtension(X.col(i), margin)) out[static_cast<std::size_t>(i)] = 2;
}

template <int Dim>
bool PuNearField<Dim>::validOnZeroSet(const Vec<Dim>& x) const {
  return pu_.validOnZeroSet(x);  // vertices as the blend accepts them: the surface ends where it did
}

template <int Dim>
double PuNearField<Dim>::lipschitzBound(const Box<Dim>& box) const {
  const double L = pu_.lipschitzBound(box);
  if (L == 0.0 && pu_.supportNear(box, reach_)) return std::numeric_limits<double>::infinity();
  return L;
}

template class PuNearField<2>;
template class PuNearField<3>;

}  // namespace hermite
