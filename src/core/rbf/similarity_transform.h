#pragma once
// Similarity transforms T(x) = q·R·x + t of fitted implicits by coefficient updates
// (docs/maths.md, Transforms). The transformed fit — the interpolant of points Tpᵢ, normals Rnᵢ, radius q·r,
// shift q·δ — equals g(x) = q·f(T⁻¹x). With y = T⁻¹x, ‖y − c‖ = ‖x − c′‖/q for c′ = Tc, and
// for a kernel homogeneous of degree k under the radius change (φ(s/q) = q⁻ᵏφ(s)):
//
//   centres c′ = T c,   α′ = q^(1−k)·α,   β′ = q^(2−k)·R β,   p′(x) = q·p(T⁻¹x)
//
// with k = 0 for the radius kernels (gaussian, wendland, multiquadric, inverse-multiquadric;
// r′ = q·r), k = 3 for cubic. Polyharmonic (x⁴ ln x, k = 4) adds a log term:
// φ(s/q) = q⁻⁴(φ(s) − ln q·s⁴), and Σ α′‖x − c′‖⁴ − β′·∇‖x − c′‖⁴ is a polynomial of degree ≤ 1
// once the coefficients annihilate the quadratics, so it is absorbed into p′.
//
// Exact (equal to the re-solve up to rounding) when λ = 0 and the polynomial degree is at least
// the kernel's order − 1 (polyharmonic: quadratic): then both are the unique interpolant.
// Otherwise g is still q·f(T⁻¹x) but no longer the re-solved fit: callers re-solve.

#include <memory>
#include <string>

#include "core/rbf/hrbf.h"
#include "core/rbf/rbf_offset.h"

namespace hermite {

// x ↦ q·R·x + t.
template <int Dim>
struct Similarity {
  Mat<Dim> R = Mat<Dim>::Identity();  // rotation (orthonormal, det +1)
  Vec<Dim> t = Vec<Dim>::Zero();
  double q = 1.0;                     // uniform scale > 0
  Vec<Dim> apply(const Vec<Dim>& x) const { return q * (R * x) + t; }
  Vec<Dim> applyInverse(const Vec<Dim>& x) const { return R.transpose() * (x - t) / q; }
  bool isIdentity() const { return q == 1.0 && t.isZero(0.0) && R == Mat<Dim>::Identity(); }
};

// Points Tpᵢ and normals Rnᵢ.
template <int Dim>
HermiteSamples<Dim> transformSamples(const HermiteSamples<Dim>& samples, const Similarity<Dim>& T);

// Whether the coefficient update equals the re-solved fit; when not, `why` says why.
bool coefficientUpdateIsExact(const Kernel& kernel, Polynomial polynomial, double smoothing, std::string* why);

// The coefficients of q·p(T⁻¹x) in the monomial order of polynomial.h.
template <int Dim>
Eigen::VectorXd transformPolynomial(Polynomial p, const Eigen::VectorXd& coefficients, const Similarity<Dim>& T);

// g = q·f(T⁻¹x) by coefficient updates (kernel radius scaled for radius kernels; RBF-offset
// shift scaled by q). Equals q·f(T⁻¹x), except for polyharmonic with a polynomial below quadratic
// and q ≠ 1: there the ln q·s⁴ term of the scaling is not a polynomial the update can absorb, and
// g is not q·f(T⁻¹x). Equals the re-solve when coefficientUpdateIsExact.
template <int Dim>
HrbfModel<Dim> transformModel(const HrbfModel<Dim>& model, const Similarity<Dim>& T);
template <int Dim>
RbfOffsetModel<Dim> transformModel(const RbfOffsetModel<Dim>& model, const Similarity<Dim>& T);

}  // namespace hermite
