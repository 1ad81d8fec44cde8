#include "core/shapes/analytic_shapes.h"

#include <cmath>
#include <string>

#include "core/base/errors.h"
#include "core/shapes/presets.h"

namespace hermite {

namespace {

// Closer than this to a singular set (where squared distances would underflow and sums of
// 1/distance terms could overflow), a point is treated as on it.
constexpr double kTiny = 1e-150;

}  // namespace

template <int Dim>
RoundField<Dim>::RoundField(const Vec<Dim>& centre, double radius) : centre_(centre), radius_(radius) {
  if (!centre.allFinite()) throw InputError("analytic field: centre must be finite");
  if (!(std::isfinite(radius) && radius > 0)) throw InputError("analytic field: radius must be finite and > 0");
}

template <int Dim>
double RoundField<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  const Vec<Dim> d = x - centre_;
  const double rho = d.norm();
  if (!(rho > kTiny)) {
    if (g) g->setZero();
    if (H) H->setZero();
    return -radius_;
  }
  const Vec<Dim> u = d / rho;
  if (g) *g = u;
  if (H) *H = (Mat<Dim>::Identity() - u * u.transpose()) / rho;
  return rho - radius_;
}

template <int Dim>
double RoundField<Dim>::lipschitzBound(const Box<Dim>&) const {
  return 1.0;
}

template class RoundField<2>;
template class RoundField<3>;

TorusField::TorusField(const Vec<3>& centre, double majorRadius, double minorRadius, const Vec<3>& axis)
    : centre_(centre), axis_(axis), major_(majorRadius), minor_(minorRadius) {
  if (!centre.allFinite()) throw InputError("torus: centre must be finite");
  if (!(std::isfinite(majorRadius) && majorRadius > 0)) throw InputError("torus: major radius must be finite and > 0");
  if (!(std::isfinite(minorRadius) && minorRadius > 0)) throw InputError("torus: minor radius must be finite and > 0");
  const double length = axis.norm();
  if (!(std::isfinite(length) && length > 0)) throw InputError("torus: axis must be finite and non-zero");
  axis_ /= length;
}

double TorusField::evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const {
  // f = D(q, h) − r with D = ‖(q − R, h)‖; q = ‖x − c − h·a‖, the distance to the axis.
  const Vec<3> d = x - centre_;
  const double h = axis_.dot(d);
  const Vec<3> radial = d - h * axis_;
  const double q = radial.norm();
  const double w = q - major_;
  const double D = std::hypot(w, h);
  const double f = D - minor_;
  if (!g && !H) return f;
  if (!(D > kTiny)) {
    if (g) g->setZero();
    if (H) H->setZero();
    return f;
  }
  const bool onAxis = !(q > kTiny);
  const Vec<3> u = onAxis ? Vec<3>::Zero() : Vec<3>(radial / q);
  const double Dq = w / D;
  const double Dh = h / D;
  if (g) *g = Dq * u + Dh * axis_;
  if (H) {
    // D's second derivatives in (q, h): (I − ŵŵᵀ)/D with ŵ = (w, h)/D. ∇q = u, ∇h = a,
    // ∇²q = (I − aaᵀ − uuᵀ)/q, ∇²h = 0.
    const double Dqq = Dh * Dh / D;
    const double Dqh = -Dq * Dh / D;
    const double Dhh = Dq * Dq / D;
    Mat<3> hessian = Dhh * axis_ * axis_.transpose();
    if (!onAxis) {
      hessian += Dq / q * (Mat<3>::Identity() - axis_ * axis_.transpose() - u * u.transpose());
      hessian += Dqq * u * u.transpose();
      hessian += Dqh * (u * axis_.transpose() + axis_ * u.transpose());
    }
    *H = hessian;
  }
  return f;
}

double TorusField::lipschitzBound(const Box<3>&) const { return 1.0; }

std::unique_ptr<ImplicitField<3>> makeAnalyticField3d(std::string_view name) {
  if (name == "sphere") return std::make_unique<SphereField>();
  if (name == "torus") {
    const TorusGeometry t = presetTori("torus").front();
    return std::make_unique<TorusField>(t.centre, t.major, t.minor, t.axis);
  }
  throw InputError("unknown analytic field '" + std::string(name) + "'; 3D fields: sphere, torus");
}

std::unique_ptr<ImplicitField<2>> makeAnalyticField2d(std::string_view name) {
  if (name == "circle") return std::make_unique<CircleField>();
  throw InputError("unknown analytic field '" + std::string(name) + "'; 2D fields: circle");
}

}  // namespace hermite
