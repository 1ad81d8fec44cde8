#pragma once
// The polynomial term p(x) of an RBF/HRBF fit (docs/maths.md, Polynomial term).
// Monomial order: none; linear = 1, x, y(, z); quadratic adds xᵢxⱼ for i ≤ j:
// 2D: 1, x, y, xx, xy, yy;  3D: 1, x, y, z, xx, xy, xz, yy, yz, zz.

#include <string_view>

#include "core/base/enum_names.h"
#include "core/base/geometry.h"

namespace hermite {

enum class Polynomial { None, Linear, Quadratic };
inline constexpr EnumName<Polynomial> kPolynomialNames[] = {
    {"none", Polynomial::None}, {"linear", Polynomial::Linear}, {"quadratic", Polynomial::Quadratic}};

std::string_view polynomialName(Polynomial p);
// Throws InputError listing none, linear, quadratic.
Polynomial parsePolynomial(std::string_view name);
int polynomialDegree(Polynomial p);  // None → −1, Linear → 1, Quadratic → 2

// Number of monomials in Dim variables.
template <int Dim>
constexpr int monomialCount(Polynomial p) {
  switch (p) {
    case Polynomial::None: return 0;
    case Polynomial::Linear: return 1 + Dim;
    case Polynomial::Quadratic: return 1 + Dim + Dim * (Dim + 1) / 2;
  }
  return 0;
}

// The most monomials a polynomial term has in Dim variables (quadratic): the fixed capacity of the
// small per-sample matrices below, which then live on the stack.
template <int Dim>
inline constexpr int kMaxMonomials = monomialCount<Dim>(Polynomial::Quadratic);

// Values (m), gradients (Dim × m) and, for the Hessian of p, nothing else is needed per monomial.
template <int Dim>
void monomials(Polynomial p, const Vec<Dim>& x, Eigen::Ref<Eigen::VectorXd> values,
               Eigen::Ref<Eigen::Matrix<double, Dim, Eigen::Dynamic>> gradients);

// p(x), ∇p(x), Hp(x) for coefficients c (m) in the order above. g and H may be null.
template <int Dim>
double evaluatePolynomial(Polynomial p, const Eigen::VectorXd& c, const Vec<Dim>& x, Vec<Dim>* g,
                          Mat<Dim>* H);

}  // namespace hermite
