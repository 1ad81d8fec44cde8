#include "core/rbf/radial_sum.h"

#include "core/rbf/radial_sum_avx512.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <omp.h>

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
      // Beyond x²/r² = 745.2 the exponential is 0 (Eigen's clamped exp gives ~1e-308 instead).
      phi = (x2 * (-1.0 / r2) >= -745.2).select((x2 * (-1.0 / r2)).exp(), 0.0);
      a = phi * (-2.0 / r2);
      if (wantE) e = phi * (4.0 / r4);
      break;
    case KernelType::Wendland: {
      for (int i = 0; i < n; ++i) {
        const double x = std::sqrt(x2p[i]);
        const double s = x / r;
        const double u = std::max(1.0 - s, 0.0);
        const double u2 = u * u;
        // Outside the support φ is 0 even where x² overflowed to inf (u² · (4s + 1) = 0 · inf).
        phip[i] = u > 0 ? u2 * u2 * (4.0 * s + 1.0) : 0.0;
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
      phi = (1.0 + x2 * (1.0 / r2)).sqrt().inverse();  // 1/√inf = 0: exact where ‖d‖² overflowed
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

// What the batch loops read: the kernel, the polynomial part and the SoA arrays (radial_sum.h)
// of centre coordinates c, α and β (bc null without β), padded to `padded` with zero coefficients.
template <int Dim>
struct BatchTerms {
  Kernel kernel;
  Polynomial polynomial;
  const Eigen::VectorXd* poly;
  Vec<Dim> origin;  // the polynomial is p(x − origin)
  const double* c[Dim];
  const double* bc[Dim];
  const double* al;
  int padded;
  bool beta;
};

#if defined(__AVX512F__)
// f (and G when WG) at every column of X by the fused AVX-512 loop (radial_sum_avx512.h), one
// instantiation per kernel T and β (B) / gradient (WG) flags.
template <int Dim, KernelType T, bool B, bool WG>
void fusedBatch(const BatchTerms<Dim>& t, const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) {
  const Eigen::Index m = X.cols();
  const double r = t.kernel.radius;
  const auto point = [&](Eigen::Index i) {
    Vec<Dim> gp;
    const Vec<Dim> xi = X.col(i);
    double fv = evaluatePolynomial<Dim>(t.polynomial, *t.poly, xi - t.origin, WG ? &gp : nullptr, nullptr);
    double g[Dim] = {};
    fv += detail::fusedSum<Dim, T, B, WG>(xi.data(), r, t.c, t.al, t.bc, t.padded, g);
    f(i) = fv;
    if constexpr (WG)
      for (int k = 0; k < Dim; ++k) (*G)(k, i) = gp(k) + g[k];
  };
  // Inside a parallel region (the PU blend's runs) on the calling thread: a nested region would
  // allocate its team on every call (blockedBatch).
  if (omp_in_parallel()) {
    for (Eigen::Index i = 0; i < m; ++i) point(i);
    return;
  }
#pragma omp parallel for schedule(dynamic, 64)
  for (Eigen::Index i = 0; i < m; ++i) point(i);
}

// The fused loop of kernel T for the β and gradient flags at hand.
template <int Dim, KernelType T>
void fusedBatchFlags(const BatchTerms<Dim>& t, const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) {
  if (t.beta) {
    if (G) fusedBatch<Dim, T, true, true>(t, X, f, G); else fusedBatch<Dim, T, true, false>(t, X, f, G);
  } else {
    if (G) fusedBatch<Dim, T, false, true>(t, X, f, G); else fusedBatch<Dim, T, false, false>(t, X, f, G);
  }
}

// The fused loop of the terms' kernel; false for a kernel type it lacks.
template <int Dim>
bool fusedBatchKernel(const BatchTerms<Dim>& t, const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) {
  using K = KernelType;
  switch (t.kernel.type) {
    case K::Cubic: fusedBatchFlags<Dim, K::Cubic>(t, X, f, G); return true;
    case K::Gaussian: fusedBatchFlags<Dim, K::Gaussian>(t, X, f, G); return true;
    case K::Wendland: fusedBatchFlags<Dim, K::Wendland>(t, X, f, G); return true;
    case K::Multiquadric: fusedBatchFlags<Dim, K::Multiquadric>(t, X, f, G); return true;
    case K::InverseMultiquadric: fusedBatchFlags<Dim, K::InverseMultiquadric>(t, X, f, G); return true;
    case K::Polyharmonic: fusedBatchFlags<Dim, K::Polyharmonic>(t, X, f, G); return true;
  }
  return false;
}
#endif

// Adds the terms of centres start … start + n − 1 at point xi of X to the value fv and the
// gradient gacc (when wantG): α φ and a α d without β; with β the HRBF terms
// f += α φ − a (β·d), ∇f += a (α d − β) − e (β·d) d. The buffers receive d = x − c per axis,
// ‖d‖² and the radial factors φ, a, e (radialBlock).
template <int Dim>
void addBlock(const BatchTerms<Dim>& t, const Points<Dim>& X, Eigen::Index xi, int start, int n, bool wantG,
              double (&d)[Dim][kBlock], double (&x2)[kBlock], double (&phi)[kBlock], double (&a)[kBlock],
              double (&e)[kBlock], double& fv, double* gacc) {
  for (int j = 0; j < n; ++j) x2[j] = 0.0;
  for (int k = 0; k < Dim; ++k) {
    const double xk = X(k, xi);
    const double* ck = t.c[k] + start;
#pragma omp simd
    for (int j = 0; j < n; ++j) {
      d[k][j] = xk - ck[j];
      x2[j] += d[k][j] * d[k][j];
    }
  }
  radialBlock(t.kernel, x2, n, phi, a, e, wantG && t.beta);
  const double* alj = t.al + start;
  // β through a local array of pointers: read through `t`, GCC vectorises the β sums below
  // differently and they round differently in the last bit.
  const double* bc[Dim];
  for (int k = 0; k < Dim; ++k) bc[k] = t.bc[k];
  double s = 0.0;
  if (!t.beta) {
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
    return;
  }
  if (!wantG) {
#pragma omp simd reduction(+ : s)
    for (int j = 0; j < n; ++j) {
      double db = 0.0;
      for (int k = 0; k < Dim; ++k) db += bc[k][start + j] * d[k][j];
      s += alj[j] * phi[j] - a[j] * db;
    }
    fv += s;
    return;
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

// f (and G) at columns begin … end − 1 of X, kBlock centres at a time through the buffers.
template <int Dim>
void blockedRange(const BatchTerms<Dim>& t, const Points<Dim>& X, Eigen::Index begin, Eigen::Index end,
                  Eigen::VectorXd& f, Points<Dim>* G) {
  const bool wantG = G != nullptr;
  // Separate arrays rather than members of one struct: GCC's vector loops over them are faster.
  alignas(64) double d[Dim][kBlock];
  alignas(64) double x2[kBlock], phi[kBlock], a[kBlock], e[kBlock];
  for (Eigen::Index i = begin; i < end; ++i) {
    Vec<Dim> gp;
    double fv = evaluatePolynomial<Dim>(t.polynomial, *t.poly, X.col(i) - t.origin, wantG ? &gp : nullptr, nullptr);
    double gacc[Dim] = {};
    for (int start = 0; start < t.padded; start += kBlock)
      addBlock<Dim>(t, X, i, start, std::min(kBlock, t.padded - start), wantG, d, x2, phi, a, e, fv, gacc);
    f(i) = fv;
    if (wantG)
      for (int k = 0; k < Dim; ++k) (*G)(k, i) = gp(k) + gacc[k];
  }
}

// f (and G) at every column of X: the portable loop, for builds without AVX-512. Threaded in
// chunks of 16 points, except inside a parallel region (the PU blend's runs, the mesher): there
// a nested region would only run on the calling thread, and entering one allocates its team —
// a malloc and free per call, per local fit, in the blend's hot loop.
template <int Dim>
void blockedBatch(const BatchTerms<Dim>& t, const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) {
  constexpr Eigen::Index kChunk = 16;
  const Eigen::Index m = X.cols();
  if (omp_in_parallel() || m <= kChunk) return blockedRange<Dim>(t, X, 0, m, f, G);
  const Eigen::Index chunks = (m + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(dynamic, 1)
  for (Eigen::Index c = 0; c < chunks; ++c) blockedRange<Dim>(t, X, c * kChunk, std::min(m, (c + 1) * kChunk), f, G);
}

}  // namespace

template <int Dim>
RadialSum<Dim>::RadialSum(Kernel kernel, Polynomial polynomial, Points<Dim> centres, Eigen::VectorXd alpha,
                          Points<Dim> beta, Eigen::VectorXd poly, Vec<Dim> polyOrigin)
    : kernel_(kernel),
      polynomial_(polynomial),
      centres_(std::move(centres)),
      alpha_(std::move(alpha)),
      beta_(std::move(beta)),
      poly_(std::move(poly)),
      polyOrigin_(polyOrigin) {
  buildSoA();
}

template <int Dim>
void RadialSum<Dim>::buildSoA() {
  const int n = static_cast<int>(centres_.cols());
  padded_ = (n + kPad - 1) / kPad * kPad;
  soa_.assign(static_cast<std::size_t>(2 * Dim + 1) * padded_, 0.0);
  const auto at = [&](int row, int j) -> double& { return soa_[static_cast<std::size_t>(row) * padded_ + j]; };
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < Dim; ++k) at(k, j) = centres_(k, j);
    at(Dim, j) = alpha_(j);
    if (hasBeta())
      for (int k = 0; k < Dim; ++k) at(Dim + 1 + k, j) = beta_(k, j);
  }
}

template <int Dim>
double RadialSum<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  Vec<Dim> gp;
  Mat<Dim> Hp;
  double f = evaluatePolynomial<Dim>(polynomial_, poly_, x - polyOrigin_, g ? &gp : nullptr, H ? &Hp : nullptr);
  Vec<Dim> gs = Vec<Dim>::Zero();
  Mat<Dim> Hs = Mat<Dim>::Zero();
  const bool beta = hasBeta();
  const double support = kernel_.supportRadius();  // infinity for global kernels
  for (Eigen::Index j = 0; j < centres_.cols(); ++j) {
    const Vec<Dim> d = x - centres_.col(j);
    // Outside a compact support every term is 0: skipped before ‖d‖² can overflow.
    if (d.cwiseAbs().maxCoeff() >= support) continue;
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
  f.resize(X.cols());
  if (G) G->resize(Dim, X.cols());
  BatchTerms<Dim> t{kernel_, polynomial_, &poly_, polyOrigin_, {}, {}, soa(Dim), padded_, hasBeta()};
  for (int k = 0; k < Dim; ++k) {
    t.c[k] = soa(k);
    t.bc[k] = t.beta ? soa(Dim + 1 + k) : nullptr;
  }
#if defined(__AVX512F__)
  if (fusedBatchKernel<Dim>(t, X, f, G)) return;
#endif
  blockedBatch<Dim>(t, X, f, G);
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
    monomials<Dim>(polynomial_, x - polyOrigin_, values, gradients);
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
    const double* al = soa(Dim);
    double lo[Dim], hi[Dim];
    const double* c[Dim];
    const double* bc[Dim];
    for (int k = 0; k < Dim; ++k) {
      lo[k] = box.lo(k);
      hi[k] = box.hi(k);
      c[k] = soa(k);
      bc[k] = beta ? soa(Dim + 1 + k) : soa(k);
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
    evaluatePolynomial<Dim>(polynomial_, poly_, box.center() - polyOrigin_, &gc, &Hc);
    // ∇p(x) = ∇p(centre) + Hp (x − centre); ‖Hp‖₂ ≤ ‖Hp‖_F.
    L += gc.norm() + Hc.norm() * 0.5 * box.extent().norm();
  }
  return L;
}

template class RadialSum<2>;
template class RadialSum<3>;

}  // namespace hermite
