#pragma once
// Analytic signed distance fields with exact gradients and Hessians (docs/maths.md, Conventions:
// f < 0 inside, ∇f points outward). References for tests, the tracers and the patch editor.
// Each is an exact distance field, so |f(x) − f(y)| ≤ ‖x − y‖ everywhere: Lipschitz bound 1.
// Where f is not differentiable (a sphere's centre, a torus's core circle and axis) evaluate
// returns finite values chosen as documented on each class; nothing is ever NaN.

#include <memory>
#include <string_view>

#include "core/base/implicit_field.h"

namespace hermite {

// f(x) = ‖x − c‖ − R: the circle (Dim 2) or sphere (Dim 3) of centre c and radius R > 0.
// At x = c (the minimum, f = −R) the gradient is 0, a subgradient, and the Hessian 0 (the true
// one grows like 1/‖x − c‖ there).
template <int Dim>
class RoundField : public ImplicitField<Dim> {
 public:
  // Throws InputError unless the radius is finite and > 0 and the centre finite.
  RoundField(const Vec<Dim>& centre, double radius);

  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override;
  double lipschitzBound(const Box<Dim>& box) const override;

  const Vec<Dim>& centre() const { return centre_; }
  double radius() const { return radius_; }

 private:
  Vec<Dim> centre_;
  double radius_;
};

class CircleField final : public RoundField<2> {
 public:
  explicit CircleField(const Vec<2>& centre = Vec<2>::Zero(), double radius = 1.0) : RoundField<2>(centre, radius) {}
};

class SphereField final : public RoundField<3> {
 public:
  explicit SphereField(const Vec<3>& centre = Vec<3>::Zero(), double radius = 1.0) : RoundField<3>(centre, radius) {}
};

// f(x) = sqrt((q − R)² + h²) − r, with h = a·(x − c) the height along the unit axis a (default z)
// and q the distance from x to that axis: the torus of major radius R > 0 and tube radius r > 0.
// On the core circle (q = R, h = 0; the minimum, f = −r) the gradient and Hessian are 0. On the
// axis (q = 0: a ridge, f has a kink across it) the subgradient drops the radial part,
// ∇f = h/D·a, and the Hessian keeps only the exact second derivative along the axis, R²/D³·aaᵀ.
class TorusField final : public ImplicitField<3> {
 public:
  // The torus preset's torus (R = 0.7, r = 0.3 about z) by default. Throws InputError unless
  // R, r > 0, the centre is finite and the axis non-zero (it is normalised).
  explicit TorusField(const Vec<3>& centre = Vec<3>::Zero(), double majorRadius = 0.7, double minorRadius = 0.3,
                      const Vec<3>& axis = Vec<3>::UnitZ());

  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override;
  double lipschitzBound(const Box<3>& box) const override;

  const Vec<3>& centre() const { return centre_; }
  const Vec<3>& axis() const { return axis_; }
  double majorRadius() const { return major_; }
  double minorRadius() const { return minor_; }

 private:
  Vec<3> centre_;
  Vec<3> axis_;
  double major_;
  double minor_;
};

// "sphere": the unit sphere; "torus": the torus preset's torus. Throws InputError listing both.
std::unique_ptr<ImplicitField<3>> makeAnalyticField3d(std::string_view name);
// "circle": the unit circle. Throws InputError.
std::unique_ptr<ImplicitField<2>> makeAnalyticField2d(std::string_view name);

extern template class RoundField<2>;
extern template class RoundField<3>;

}  // namespace hermite
