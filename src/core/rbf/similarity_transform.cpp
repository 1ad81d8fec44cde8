#include "core/rbf/similarity_transform.h"

#include <cmath>
#include <utility>

namespace hermite {

template <int Dim>
HermiteSamples<Dim> transformSamples(const HermiteSamples<Dim>& samples, const Similarity<Dim>& T) {
  HermiteSamples<Dim> out;
  out.points = (T.q * (T.R * samples.points)).colwise() + T.t;
  out.normals = T.R * samples.normals;
  return out;
}

bool coefficientUpdateIsExact(const Kernel& kernel, Polynomial polynomial, double smoothing, std::string* why) {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (smoothing != 0)
    return fail("smoothing λ ≠ 0: the smoothed fit does not scale with the data, so it is re-solved");
  if (polynomialDegree(polynomial) < kernel.cpdOrder() - 1)
    return fail("polynomial '" + std::string(polynomialName(polynomial)) + "' is below the order of kernel '" +
                std::string(kernelName(kernel.type)) + "': the interpolant is not unique, so it is re-solved");
  if (kernel.type == KernelType::Polyharmonic && polynomial != Polynomial::Quadratic)
    return fail("polyharmonic needs the quadratic term for an exact update");
  return true;
}

template <int Dim>
Eigen::VectorXd transformPolynomial(Polynomial p, const Eigen::VectorXd& c, const Similarity<Dim>& T) {
  if (p == Polynomial::None) return c;
  // p(y) = c₀ + gᵀy + yᵀQy with y = A x + b, A = Rᵀ/q, b = −Rᵀt/q; times q.
  Vec<Dim> g;
  Mat<Dim> Q = Mat<Dim>::Zero();
  for (int i = 0; i < Dim; ++i) g(i) = c(1 + i);
  if (p == Polynomial::Quadratic) {
    int k = 1 + Dim;
    for (int i = 0; i < Dim; ++i)
      for (int j = i; j < Dim; ++j, ++k) {
        if (i == j) {
          Q(i, i) = c(k);
        } else {
          Q(i, j) = Q(j, i) = 0.5 * c(k);
        }
      }
  }
  const Mat<Dim> A = T.R.transpose() / T.q;
  const Vec<Dim> b = -A * T.t;
  const double c0 = T.q * (c(0) + g.dot(b) + b.dot(Q * b));
  const Vec<Dim> g1 = T.q * (A.transpose() * (g + 2.0 * Q * b));
  const Mat<Dim> Q1 = T.q * (A.transpose() * Q * A);
  Eigen::VectorXd out(c.size());
  out(0) = c0;
  for (int i = 0; i < Dim; ++i) out(1 + i) = g1(i);
  if (p == Polynomial::Quadratic) {
    int k = 1 + Dim;
    for (int i = 0; i < Dim; ++i)
      for (int j = i; j < Dim; ++j, ++k) out(k) = i == j ? Q1(i, i) : Q1(i, j) + Q1(j, i);
  }
  return out;
}

namespace {

// Degree k of φ(s/q) = q⁻ᵏ φ(s) (radius kernels: 0, their radius scales instead).
int homogeneity(KernelType t) {
  if (t == KernelType::Cubic) return 3;
  if (t == KernelType::Polyharmonic) return 4;
  return 0;
}

// Coefficients (constant, gradient) of Σⱼ αⱼ‖x − cⱼ‖⁴ − βⱼ·∇‖x − cⱼ‖⁴, a polynomial of degree ≤ 1
// when (α, β) annihilate the quadratics: its value and gradient at x = 0.
template <int Dim>
std::pair<double, Vec<Dim>> quarticSumAtOrigin(const Points<Dim>& C, const Eigen::VectorXd& alpha, const Points<Dim>* beta) {
  double value = 0;
  Vec<Dim> grad = Vec<Dim>::Zero();
  for (Eigen::Index j = 0; j < C.cols(); ++j) {
    const Vec<Dim> c = C.col(j);
    const double c2 = c.squaredNorm();
    // ‖x − c‖⁴ at 0: c2²; ∇ = 4‖x − c‖²(x − c) → −4 c2 c.
    value += alpha(j) * c2 * c2;
    grad += alpha(j) * (-4.0 * c2 * c);
    if (beta) {
      const Vec<Dim> bj = beta->col(j);
      // −β·∇‖x − c‖⁴ = −4‖x − c‖² β·(x − c): at 0 → 4 c2 (β·c);
      // its gradient −4[2(x − c)(β·(x − c)) + ‖x − c‖² β] at 0 → −4[2c(β·c) + c2 β].
      value += 4.0 * c2 * bj.dot(c);
      grad += -4.0 * (2.0 * c * bj.dot(c) + c2 * bj);
    }
  }
  return {value, grad};
}

// The transformed polynomial and its origin o′. With origin o, p(T⁻¹x − o) = p(L⁻¹(x − T o)) for
// L = q·R: the new polynomial is q·p(L⁻¹y) about o′ = T o (the translation moves the origin
// only). A model without origin keeps the translation in the coefficients, as before.
template <int Dim>
std::pair<Eigen::VectorXd, Vec<Dim>> transformedPoly(const RadialSum<Dim>& m, const Similarity<Dim>& T,
                                                     const Points<Dim>& centres, const Eigen::VectorXd& alpha,
                                                     const Points<Dim>* beta) {
  const bool centred = !m.polyOrigin().isZero();
  Similarity<Dim> linear = T;
  if (centred) linear.t.setZero();
  const Vec<Dim> origin = centred ? T.apply(m.polyOrigin()) : Vec<Dim>::Zero();
  Eigen::VectorXd poly = transformPolynomial<Dim>(m.polynomial(), m.poly(), linear);
  if (m.kernel().type == KernelType::Polyharmonic && T.q != 1.0 && poly.size() >= 1 + Dim) {
    const Points<Dim> relative = centres.colwise() - origin;
    const auto [v, g] = quarticSumAtOrigin<Dim>(relative, alpha, beta);
    const double lnq = std::log(T.q);
    poly(0) -= lnq * v;
    for (int i = 0; i < Dim; ++i) poly(1 + i) -= lnq * g(i);
  }
  return {std::move(poly), origin};
}

}  // namespace

template <int Dim>
HrbfModel<Dim> transformModel(const HrbfModel<Dim>& m, const Similarity<Dim>& T) {
  const int k = homogeneity(m.kernel().type);
  Kernel kernel = m.kernel();
  if (kernel.usesRadius()) kernel.radius *= T.q;
  const Points<Dim> centres = (T.q * (T.R * m.centres())).colwise() + T.t;
  const Eigen::VectorXd alpha = std::pow(T.q, 1 - k) * m.alpha();
  const Points<Dim> beta = std::pow(T.q, 2 - k) * (T.R * m.beta());
  auto [poly, origin] = transformedPoly<Dim>(m, T, centres, alpha, &beta);
  return HrbfModel<Dim>(kernel, m.polynomial(), centres, alpha, beta, std::move(poly), origin);
}

template <int Dim>
RbfOffsetModel<Dim> transformModel(const RbfOffsetModel<Dim>& m, const Similarity<Dim>& T) {
  const int k = homogeneity(m.kernel().type);
  Kernel kernel = m.kernel();
  if (kernel.usesRadius()) kernel.radius *= T.q;
  const Points<Dim> centres = (T.q * (T.R * m.centres())).colwise() + T.t;
  const Eigen::VectorXd w = std::pow(T.q, 1 - k) * m.alpha();
  auto [poly, origin] = transformedPoly<Dim>(m, T, centres, w, nullptr);
  return RbfOffsetModel<Dim>(kernel, m.polynomial(), centres, w, std::move(poly), T.q * m.shift(), origin);
}

template HermiteSamples<2> transformSamples<2>(const HermiteSamples<2>&, const Similarity<2>&);
template HermiteSamples<3> transformSamples<3>(const HermiteSamples<3>&, const Similarity<3>&);
template Eigen::VectorXd transformPolynomial<2>(Polynomial, const Eigen::VectorXd&, const Similarity<2>&);
template Eigen::VectorXd transformPolynomial<3>(Polynomial, const Eigen::VectorXd&, const Similarity<3>&);
template HrbfModel<2> transformModel<2>(const HrbfModel<2>&, const Similarity<2>&);
template HrbfModel<3> transformModel<3>(const HrbfModel<3>&, const Similarity<3>&);
template RbfOffsetModel<2> transformModel<2>(const RbfOffsetModel<2>&, const Similarity<2>&);
template RbfOffsetModel<3> transformModel<3>(const RbfOffsetModel<3>&, const Similarity<3>&);

}  // namespace hermite
