#include "core/rbf/polynomial.h"

#include <string>

#include "core/base/errors.h"

namespace hermite {

std::string_view polynomialName(Polynomial p) { return nameIn<Polynomial>(kPolynomialNames, p); }

Polynomial parsePolynomial(std::string_view name) {
  if (const auto value = valueIn<Polynomial>(kPolynomialNames, name)) return *value;
  throw InputError("unknown polynomial '" + std::string(name) + "', expected one of: " +
                   namesIn<Polynomial>(kPolynomialNames));
}

int polynomialDegree(Polynomial p) {
  switch (p) {
    case Polynomial::None: return -1;
    case Polynomial::Linear: return 1;
    case Polynomial::Quadratic: return 2;
  }
  return -1;
}

template <int Dim>
void monomials(Polynomial p, const Vec<Dim>& x, Eigen::Ref<Eigen::VectorXd> values,
               Eigen::Ref<Eigen::Matrix<double, Dim, Eigen::Dynamic>> gradients) {
  if (p == Polynomial::None) return;
  values(0) = 1.0;
  gradients.col(0).setZero();
  for (int i = 0; i < Dim; ++i) {
    values(1 + i) = x(i);
    gradients.col(1 + i).setZero();
    gradients(i, 1 + i) = 1.0;
  }
  if (p == Polynomial::Linear) return;
  int k = 1 + Dim;
  for (int i = 0; i < Dim; ++i) {
    for (int j = i; j < Dim; ++j, ++k) {
      values(k) = x(i) * x(j);
      gradients.col(k).setZero();
      gradients(i, k) += x(j);
      gradients(j, k) += x(i);
    }
  }
}

template <int Dim>
double evaluatePolynomial(Polynomial p, const Eigen::VectorXd& c, const Vec<Dim>& x, Vec<Dim>* g,
                          Mat<Dim>* H) {
  if (g) g->setZero();
  if (H) H->setZero();
  if (p == Polynomial::None) return 0.0;
  double f = c(0);
  for (int i = 0; i < Dim; ++i) {
    f += c(1 + i) * x(i);
    if (g) (*g)(i) += c(1 + i);
  }
  if (p == Polynomial::Quadratic) {
    int k = 1 + Dim;
    for (int i = 0; i < Dim; ++i) {
      for (int j = i; j < Dim; ++j, ++k) {
        f += c(k) * x(i) * x(j);
        if (g) {
          (*g)(i) += c(k) * x(j);
          (*g)(j) += c(k) * x(i);
        }
        if (H) {
          (*H)(i, j) += c(k);
          (*H)(j, i) += c(k);
        }
      }
    }
  }
  return f;
}

template void monomials<2>(Polynomial, const Vec<2>&, Eigen::Ref<Eigen::VectorXd>,
                           Eigen::Ref<Eigen::Matrix<double, 2, Eigen::Dynamic>>);
template void monomials<3>(Polynomial, const Vec<3>&, Eigen::Ref<Eigen::VectorXd>,
                           Eigen::Ref<Eigen::Matrix<double, 3, Eigen::Dynamic>>);
template double evaluatePolynomial<2>(Polynomial, const Eigen::VectorXd&, const Vec<2>&, Vec<2>*, Mat<2>*);
template double evaluatePolynomial<3>(Polynomial, const Eigen::VectorXd&, const Vec<3>&, Vec<3>*, Mat<3>*);

}  // namespace hermite
