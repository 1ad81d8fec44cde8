#include "core/rbf/kernels.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "core/base/errors.h"

namespace hermite {

namespace {

// Each kernel as (x, r) → RadialTerms. Formulas derived by hand from φ; s = x/r.
RadialTerms gaussianTerms(double x, double r) {
  if (!std::isfinite(x * x)) return {};  // every factor's limit is 0; the formulas give 0 · inf
  const double r2 = r * r;
  const double p = std::exp(-(x * x) / r2);
  RadialTerms t;
  t.phi = p;
  t.dphi = -2.0 * x / r2 * p;
  t.a = -2.0 / r2 * p;
  t.b = 4.0 * x * x / (r2 * r2) * p;
  t.e = 4.0 / (r2 * r2) * p;
  t.g = -8.0 / (r2 * r2 * r2) * p;
  return t;
}

// (1 − s)⁴₊(4s + 1): Wendland ψ₃,₁, C², positive definite up to 3D.
RadialTerms wendlandTerms(double x, double r) {
  RadialTerms t;
  const double s = x / r;
  if (s >= 1.0) return t;
  const double u = 1.0 - s;
  const double u2 = u * u, u3 = u2 * u;
  const double r2 = r * r, r3 = r2 * r;
  t.phi = u3 * u * (4.0 * s + 1.0);
  t.dphi = -20.0 * x * u3 / r2;
  t.a = -20.0 * u3 / r2;
  t.b = 60.0 * x * u2 / r3;
  if (x > 0) {
    t.e = 60.0 * u2 / (r3 * x);
    t.g = -60.0 * u * (1.0 + s) / (r3 * x * x * x);
  }
  return t;
}

// √(1 + s²): conditionally negative definite of order 1.
RadialTerms multiquadricTerms(double x, double r) {
  const double r2 = r * r;
  const double p = std::sqrt(1.0 + x * x / r2);
  RadialTerms t;
  t.phi = p;
  t.dphi = x / (r2 * p);
  t.a = 1.0 / (r2 * p);
  t.b = -x * x / (r2 * r2 * p * p * p);
  t.e = -1.0 / (r2 * r2 * p * p * p);
  t.g = 3.0 / (r2 * r2 * r2 * p * p * p * p * p);
  return t;
}

// 1/√(1 + s²): positive definite.
RadialTerms inverseMultiquadricTerms(double x, double r) {
  if (!std::isfinite(x * x)) return {};  // every factor's limit is 0; the formulas give 0 · inf
  const double r2 = r * r;
  const double p = 1.0 / std::sqrt(1.0 + x * x / r2);
  const double p3 = p * p * p, p5 = p3 * p * p;
  RadialTerms t;
  t.phi = p;
  t.dphi = -x / r2 * p3;
  t.a = -p3 / r2;
  t.b = 3.0 * x * x * p5 / (r2 * r2);
  t.e = 3.0 * p5 / (r2 * r2);
  t.g = -15.0 * p5 * p * p / (r2 * r2 * r2);
  return t;
}

// x³: conditionally positive definite of order 2.
RadialTerms cubicTerms(double x) {
  RadialTerms t;
  t.phi = x * x * x;
  t.dphi = 3.0 * x * x;
  t.a = 3.0 * x;
  t.b = 3.0 * x;
  if (x > 0) {
    t.e = 3.0 / x;
    t.g = -3.0 / (x * x * x);
  }
  return t;
}

// x⁴ ln x: conditionally negative definite of order 3. All factors → 0 at x = 0 except e, g
// (logarithmic / 1/x² growth, always multiplied by enough powers of d).
RadialTerms polyharmonicTerms(double x) {
  RadialTerms t;
  if (!(x > 0)) return t;
  const double lx = std::log(x);
  const double x2 = x * x;
  t.phi = x2 * x2 * lx;
  t.dphi = x2 * x * (4.0 * lx + 1.0);
  t.a = x2 * (4.0 * lx + 1.0);
  t.b = x2 * (8.0 * lx + 6.0);
  t.e = 8.0 * lx + 6.0;
  t.g = 8.0 / x2;
  return t;
}

}  // namespace

RadialTerms Kernel::terms(double x) const {
  switch (type) {
    case KernelType::Gaussian: return gaussianTerms(x, radius);
    case KernelType::Wendland: return wendlandTerms(x, radius);
    case KernelType::Multiquadric: return multiquadricTerms(x, radius);
    case KernelType::InverseMultiquadric: return inverseMultiquadricTerms(x, radius);
    case KernelType::Cubic: return cubicTerms(x);
    case KernelType::Polyharmonic: return polyharmonicTerms(x);
  }
  return {};
}

RadialBounds Kernel::bounds(double lo, double hi) const {
  // Interior critical points of |φ′|, |a| and |φ″| (in x), found by hand per kernel. The
  // sup of a smooth function over [lo, hi] is attained at an endpoint or a critical point.
  // (A fixed array: this runs for every centre of every brick of a bake.)
  double candidates[5] = {lo, hi};
  int count = 2;
  const double r = radius;
  auto add = [&](std::initializer_list<double> xs) {
    for (double x : xs) candidates[count++] = x;
  };
  switch (type) {
    case KernelType::Gaussian:  // φ′: s = 1/√2; φ″: s = √1.5
      add({r / std::sqrt(2.0), r * std::sqrt(1.5)});
      break;
    case KernelType::Wendland:  // φ′: s = 1/4; φ″: s = 1/2
      add({0.25 * r, 0.5 * r});
      break;
    case KernelType::InverseMultiquadric:  // φ′: s = 1/√2; φ″: s = √1.5
      add({r / std::sqrt(2.0), r * std::sqrt(1.5)});
      break;
    case KernelType::Multiquadric:  // φ′ increasing, a and φ″ decreasing: the endpoints
      break;
    case KernelType::Cubic:  // |φ′| = 3x², |a| = 3x, |φ″| = 6x all increasing: the sups are at hi
      candidates[0] = hi;
      count = 1;
      break;
    case KernelType::Polyharmonic:  // φ′: x = e^{−7/12}; a: e^{−3/4}; φ″: e^{−13/12}
      add({std::exp(-7.0 / 12.0), std::exp(-0.75), std::exp(-13.0 / 12.0)});
      break;
  }
  RadialBounds out;
  for (int q = 0; q < count; ++q) {
    const double x = candidates[q];
    if (x < lo || x > hi) continue;
    const RadialTerms t = terms(x);
    out.dphi = std::max(out.dphi, std::abs(t.dphi));
    out.hessian = std::max({out.hessian, std::abs(t.a), std::abs(t.ddphi())});
  }
  return out;
}

bool Kernel::usesRadius() const {
  return type != KernelType::Cubic && type != KernelType::Polyharmonic;
}

int Kernel::cpdOrder() const {
  switch (type) {
    case KernelType::Gaussian:
    case KernelType::Wendland:
    case KernelType::InverseMultiquadric: return 0;
    case KernelType::Multiquadric: return 1;
    case KernelType::Cubic: return 2;
    case KernelType::Polyharmonic: return 3;
  }
  return 0;
}

double Kernel::smoothingSign() const {
  return (type == KernelType::Multiquadric || type == KernelType::Polyharmonic) ? -1.0 : 1.0;
}

double Kernel::supportRadius() const {
  return type == KernelType::Wendland ? radius : std::numeric_limits<double>::infinity();
}

static_assert([] {
  for (std::size_t i = 0; i < kKernelTable.size(); ++i)
    if (static_cast<std::size_t>(kKernelTable[i].type) != i || kKernelTable[i].id != int(i)) return false;
  return true;
}(), "kKernelTable: rows in enum order, id = row");

const KernelInfo& kernelInfo(KernelType t) { return kKernelTable.at(static_cast<std::size_t>(t)); }

std::string_view kernelName(KernelType t) { return kernelInfo(t).name; }

const std::vector<KernelType>& allKernelTypes() {
  static const std::vector<KernelType> all = [] {
    std::vector<KernelType> types;
    for (const KernelInfo& k : kKernelTable) types.push_back(k.type);
    return types;
  }();
  return all;
}

KernelType parseKernelType(std::string_view name) {
  for (KernelType t : allKernelTypes())
    if (kernelName(t) == name) return t;
  if (name == "thin-plate" || name == "thin-plate-spline" || name == "tps")
    throw InputError("kernel '" + std::string(name) +
                     "' (x² ln x) cannot carry Hermite data: φ′(x)/x = 2 ln x + 1 has no limit "
                     "at x = 0, so the gradient conditions are undefined at the centres");
  if (name == "linear")
    throw InputError("kernel 'linear' (x) cannot carry Hermite data: φ′(x)/x = 1/x has no limit at x = 0");
  std::string valid;
  for (KernelType t : allKernelTypes()) valid += (valid.empty() ? "" : ", ") + std::string(kernelName(t));
  throw InputError("unknown kernel '" + std::string(name) + "', expected one of: " + valid);
}

}  // namespace hermite
