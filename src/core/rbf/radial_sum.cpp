#include "core/rbf/radial_sum.h"

#include "core/rbf/radial_sum_avx512.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace hermite {

namespace {

constexpr int kPad = 8;      // SoA padding: one AVX-512 vector of doubles
constexpr int kBlock = 256;  // centres per block in the batch loops (buffers stay in L1)

// Radial factors for a block of squared distances x2 (n entries): φ, a = φ′/x, e = a′/x
// (e only when wantE). Vectorised through Eigen array expressions (Eigen's exp/log are SIMD).
void radialBlock(const Kernel& k, const double* x2p, int n, double* phip, double* ap, double* ep, bool wantE) {
  using Arr = Eigen::Map<Eigen::ArrayXd>;
  using CArr = Eigen::Map<const Eigen::ArrayXd>;
  const CArr x2(x2p, n);
  Arr phi(phip, n), a(ap, n), e(ep, n);
  const double r = k.radius, r2 = r * r, r4 = r2 * r2;
  switch (k.type) {
    case KernelType::Gaussian:
      phi = (x2 * (-1.0 / r2)).exp();
      a = phi * (-2.0 / r2);
      if (wantE) e = phi * (4.0 / r4);
      break;
    case KernelType::Wendland: {
      for (int i = 0; i < n; ++i) {
        const double x = std::sqrt(x2p[i]);
        const double s = x / r;
        const double u = std::max(1.0 - s, 0.0);
        const double u2 = u * u;
        phip[i] = u2 * u2 * (4.0 * s + 1.0);
        ap[i] = -20.0 * u2 * u / r2;
        if (wantE) ep[i] = x > 0 ? 60.0 * u2 / (r2 * r * x) : 0.0;
      }
      break;
    }
    case KernelType::Multiquadric:
      phi = (1.0 + x2 * (1.0 / r2)).sqrt();
      a = (1.0 / r2) / phi;
      if (wantE) e = (-1.0 / r4) / (phi * phi * phi);
      break;
    case KernelType::InverseMultiquadric:
      phi = (1.0 + x2 * (1.0 / r2)).sqrt().inverse();
      a = phi.cube() * (-1.0 / r2);
      if (wantE) e = phi.cube() * phi.square() * (3.0 / r4);
      break;
    case KernelType::Cubic:
      for (int i = 0; i < n; ++i) {
        const double x = std::sqrt(x2p[i]);
        phip[i] = x2p[i] * x;
        ap[i] = 3.0 * x;
        if (wantE) ep[i] = x > 0 ? 3.0 / x : 0.0;
      }
      break;
    case KernelType::Polyharmonic: {
      // ln x = ½ ln x²; x² = 0 gives −inf, replaced by the exact limits (0).
      Eigen::ArrayXd lx = 0.5 * x2.log();
      const auto pos = x2 > 0.0;
      phi = pos.select(x2.square() * lx, 0.0);
      a = pos.select(x2 * (4.0 * lx + 1.0), 0.0);
      if (wantE) e = pos.select(8.0 * lx + 6.0, 0.0);
      break;
    }
  }
}

}  // namespace

template <int Dim>
RadialSum<Dim>::RadialSum(Kernel kernel, Polynomial polynomial, Points<Dim> centres, Eigen::VectorXd alpha,
                          Points<Dim> beta, Eigen::VectorXd poly)
    : kernel_(kernel),
      polynomial_(polynomial),
      centres_(std::move(centres)),
      alpha_(std::move(alpha)),
      beta_(std::move(beta)),
      poly_(std::move(poly)) {
  buildSoA();
}

template <int Dim>
void RadialSum<Dim>::buildSoA() {
  const int n = static_cast<int>(centres_.cols());
  padded_ = (n + kPad - 1) / kPad * kPad;
  soa_.assign(2 * Dim + 1, std::vector<double>(padded_, 0.0));
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < Dim; ++k) soa_[k][j] = centres_(k, j);
    soa_[Dim][j] = alpha_(j);
    if (hasBeta())
      for (int k = 0; k < Dim; ++k) soa_[Dim + 1 + k][j] = beta_(k, j);
  }
}

template <int Dim>
double RadialSum<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  Vec<Dim> gp;
  Mat<Dim> Hp;
  double f = evaluatePolynomial<Dim>(polynomial_, poly_, x, g ? &gp : nullptr, H ? &Hp : nullptr);
  Vec<Dim> gs = Vec<Dim>::Zero();
  Mat<Dim> Hs = Mat<Dim>::Zero();
  const bool beta = hasBeta();
  for (Eigen::Index j = 0; j < centres_.cols(); ++j) {
    const Vec<Dim> d = x - centres_.col(j);
    const RadialTerms t = kernel_.terms(d.norm());
    const double aj = alpha_(j);
    f += aj * t.phi;
    if (g) gs += aj * t.a * d;
    if (H) Hs += aj * (t.a * Mat<Dim>::Identity() + t.e * d * d.transpose());
    if (beta) {
      const Vec<Dim> bj = beta_.col(j);
      const double db = d.dot(bj);
      f -= t.a * db;  // −β·∇φ = −a (β·d)
      if (g) gs -= t.a * bj + t.e * db * d;  // −Hφ β
      if (H) {
        // −Σₖ βₖ ∂ᵢⱼₖφ = −[e(d βᵀ + β dᵀ + (d·β) I) + g (d·β) d dᵀ]
        Hs -= t.e * (d * bj.transpose() + bj * d.transpose() + db * Mat<Dim>::Identity()) +
              t.g * db * d * d.transpose();
      }
    }
  }
  if (g) *g = gp + gs;
  if (H) *H = Hp + Hs;
  return f;
}

template <int Dim>
void RadialSum<Dim>::evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) const {
  const Eigen::Index m = X.cols();
  f.resize(m);
  if (G) G->resize(Dim, m);
  const bool wantG = G != nullptr;
  const bool beta = hasBeta();
  const double* c[Dim];
  const double* bc[Dim];
  for (int k = 0; k < Dim; ++k) {
    c[k] = soa_[k].data();
    bc[k] = beta ? soa_[Dim + 1 + k].data() : nullptr;
  }
  const double* al = soa_[Dim].data();

#if defined(__AVX512F__)
  // Fused AVX-512 path: one templated loop per (kernel, β?, gradient?) combination.
  auto run = [&](auto kernelTag, auto betaTag, auto gradTag) {
    constexpr KernelType T = decltype(kernelTag)::value;
    constexpr bool B = decltype(betaTag)::value, WG = decltype(gradTag)::value;
    const double r = kernel_.radius;
#pragma omp parallel for schedule(dynamic, 64)
    for (Eigen::Index i = 0; i < m; ++i) {
      Vec<Dim> gp;
      const Vec<Dim> xi = X.col(i);
      double fv = evaluatePolynomial<Dim>(polynomial_, poly_, xi, WG ? &gp : nullptr, nullptr);
      double g[Dim] = {};
      fv += detail::fusedSum<Dim, T, B, WG>(xi.data(), r, c, al, bc, padded_, g);
      f(i) = fv;
      if constexpr (WG)
        for (int k = 0; k < Dim; ++k) (*G)(k, i) = gp(k) + g[k];
    }
  };
  auto withFlags = [&](auto kernelTag) {
    using TT = std::true_type;
    using FT = std::false_type;
    if (beta) {
      if (wantG) run(kernelTag, TT{}, TT{}); else run(kernelTag, TT{}, FT{});
    } else {
      if (wantG) run(kernelTag, FT{}, TT{}); else run(kernelTag, FT{}, FT{});
    }
  };
  switch (kernel_.type) {
    case KernelType::Cubic: withFlags(std::integral_constant<KernelType, KernelType::Cubic>{}); return;
    case KernelType::Gaussian: withFlags(std::integral_constant<KernelType, KernelType::Gaussian>{}); return;
    case KernelType::Wendland: withFlags(std::integral_constant<KernelType, KernelType::Wendland>{}); return;
    case KernelType::Multiquadric: withFlags(std::integral_constant<KernelType, KernelType::Multiquadric>{}); return;
    case KernelType::InverseMultiquadric:
      withFlags(std::integral_constant<KernelType, KernelType::InverseMultiquadric>{});
      return;
    case KernelType::Polyharmonic: withFlags(std::integral_constant<KernelType, KernelType::Polyharmonic>{}); return;
  }
#endif

#pragma omp parallel
  {
    alignas(64) double d[Dim][kBlock];
    alignas(64) double x2[kBlock], phi[kBlock], a[kBlock], e[kBlock];
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index i = 0; i < m; ++i) {
      Vec<Dim> gp;
      double fv = evaluatePolynomial<Dim>(polynomial_, poly_, X.col(i), wantG ? &gp : nullptr, nullptr);
      double gacc[Dim] = {};
      for (int start = 0; start < padded_; start += kBlock) {
        const int n = std::min(kBlock, padded_ - start);
        for (int j = 0; j < n; ++j) x2[j] = 0.0;
        for (int k = 0; k < Dim; ++k) {
          const double xk = X(k, i);
          const double* ck = c[k] + start;
#pragma omp simd
          for (int j = 0; j < n; ++j) {
            d[k][j] = xk - ck[j];
            x2[j] += d[k][j] * d[k][j];
          }
        }
        radialBlock(kernel_, x2, n, phi, a, e, wantG && beta);
        const double* alj = al + start;
        if (!beta) {
          double s = 0.0;
#pragma omp simd reduction(+ : s)
          for (int j = 0; j < n; ++j) s += alj[j] * phi[j];
          fv += s;
          if (wantG) {
            for (int k = 0; k < Dim; ++k) {
              double sk = 0.0;
#pragma omp simd reduction(+ : sk)
              for (int j = 0; j < n; ++j) sk += alj[j] * a[j] * d[k][j];
              gacc[k] += sk;
            }
          }
          continue;
        }
        // HRBF: f += α φ − a (β·d);  ∇f += a (α d − β) − e (β·d) d
        double s = 0.0;
        if (!wantG) {
#pragma omp simd reduction(+ : s)
          for (int j = 0; j < n; ++j) {
            double db = 0.0;
            for (int k = 0; k < Dim; ++k) db += bc[k][start + j] * d[k][j];
            s += alj[j] * phi[j] - a[j] * db;
          }
          fv += s;
          continue;
        }
        double g0 = 0.0, g1 = 0.0, g2 = 0.0;
#pragma omp simd reduction(+ : s, g0, g1, g2)
        for (int j = 0; j < n; ++j) {
          double db = 0.0;
          for (int k = 0; k < Dim; ++k) db += bc[k][start + j] * d[k][j];
          s += alj[j] * phi[j] - a[j] * db;
          const double ed = e[j] * db;
          g0 += a[j] * (alj[j] * d[0][j] - bc[0][start + j]) - ed * d[0][j];
          g1 += a[j] * (alj[j] * d[1][j] - bc[1][start + j]) - ed * d[1][j];
          if constexpr (Dim == 3) g2 += a[j] * (alj[j] * d[2][j] - bc[2][start + j]) - ed * d[2][j];
        }
        fv += s;
        gacc[0] += g0;
        gacc[1] += g1;
        if constexpr (Dim == 3) gacc[2] += g2;
      }
      f(i) = fv;
      if (wantG)
        for (int k = 0; k < Dim; ++k) (*G)(k, i) = gp(k) + gacc[k];
    }
  }
}

template <int Dim>
double RadialSum<Dim>::termMagnitude(const Vec<Dim>& x) const {
  double sum = 0.0;
  for (Eigen::Index j = 0; j < centres_.cols(); ++j) {
    const Vec<Dim> d = x - centres_.col(j);
    const RadialTerms t = kernel_.terms(d.norm());
    sum += std::abs(alpha_(j) * t.phi);
    if (hasBeta()) sum += std::abs(t.a * d.dot(beta_.col(j)));  // ∇φ(d) = a·d
  }
  if (polynomial_ != Polynomial::None) {
    const int m = monomialCount<Dim>(polynomial_);
    Eigen::VectorXd values(m);
    Eigen::Matrix<double, Dim, Eigen::Dynamic> gradients(Dim, m);
    monomials<Dim>(polynomial_, x, values, gradients);
    sum += (poly_.array() * values.array()).abs().sum();
  }
  return sum;
}

template <int Dim>
double RadialSum<Dim>::lipschitzBound(const Box<Dim>& box) const {
  // ‖∇f‖ ≤ Σⱼ |αⱼ| sup|φ′| + ‖βⱼ‖ sup‖Hφ‖ + sup‖∇p‖ over the box; ‖Hφ‖₂ = max(|a|, |φ″|).
  double L = 0.0;
  if (kernel_.type == KernelType::Cubic) {
    // φ′ = 3x², a = 3x, φ″ = 6x all increase on x ≥ 0: the sups are at the farthest corner,
    // sup|φ′| = 3 hi², sup‖Hφ‖ = 6 hi. One vectorised pass over the SoA centres (padding
    // centres have zero coefficients).
    const bool beta = hasBeta();
    const double* al = soa_[Dim].data();
    double lo[Dim], hi[Dim];
    const double* c[Dim];
    const double* bc[Dim];
    for (int k = 0; k < Dim; ++k) {
      lo[k] = box.lo(k);
      hi[k] = box.hi(k);
      c[k] = soa_[k].data();
      bc[k] = beta ? soa_[Dim + 1 + k].data() : soa_[k].data();
    }
    double sumA = 0.0, sumB = 0.0;
#pragma omp simd reduction(+ : sumA, sumB)
    for (int j = 0; j < padded_; ++j) {
      double far2 = 0.0, b2 = 0.0;
      for (int k = 0; k < Dim; ++k) {
        const double e = std::max(std::abs(c[k][j] - lo[k]), std::abs(hi[k] - c[k][j]));
        far2 += e * e;
        b2 += bc[k][j] * bc[k][j];
      }
      sumA += std::abs(al[j]) * (3.0 * far2);
      sumB += beta ? std::sqrt(b2) * (6.0 * std::sqrt(far2)) : 0.0;
    }
    L = sumA + sumB;
  } else {
    for (Eigen::Index j = 0; j < centres_.cols(); ++j) {
      const Vec<Dim> cj = centres_.col(j);
      const RadialBounds rb = kernel_.bounds(box.distanceTo(cj), box.farthestDistance(cj));
      L += std::abs(alpha_(j)) * rb.dphi;
      if (hasBeta()) L += beta_.col(j).norm() * rb.hessian;
    }
  }
  if (polynomial_ != Polynomial::None) {
    Vec<Dim> gc;
    Mat<Dim> Hc;
    evaluatePolynomial<Dim>(polynomial_, poly_, box.center(), &gc, &Hc);
    // ∇p(x) = ∇p(centre) + Hp (x − centre); ‖Hp‖₂ ≤ ‖Hp‖_F.
    L += gc.norm() + Hc.norm() * 0.5 * box.extent().norm();
  }
  return L;
}

template class RadialSum<2>;
template class RadialSum<3>;

}  // namespace hermite
