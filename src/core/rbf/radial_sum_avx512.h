#pragma once
// AVX-512 fused evaluation loop of RadialSum, shared by RadialSum::evaluateBatch (radial_sum.cpp)
// and the volume bake (core/trace/volume_bake.cpp); compiled only where __AVX512F__ is defined.
//
// One pass over the centres, 8 at a time, computes d, ‖d‖², the radial factors and the sums,
// with nothing stored in between. Square roots and divisions are the bottleneck of the generic
// path (vsqrtpd + vdivpd ≈ 32 cycles per 8 pairs); here 1/‖d‖ comes from vrsqrt14pd refined by
// two Newton steps (14 → 28 → ~53 bits; a few ulp, no division), and exp / log from Eigen's
// packet functions. docs/performance.md has the per-pair timings against the generic path.

#if defined(__AVX512F__)

#include <immintrin.h>

#include <limits>

#include <Eigen/Core>

#include "core/rbf/kernels.h"

// GCC 12 flags _mm512_undefined_pd() inside the rsqrt14 intrinsic as uninitialised (false positive).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"

namespace hermite::detail {

// 1/√x per lane, 0 where x = 0 (the limits then make every factor exact at a centre).
inline __m512d invSqrt(__m512d x) {
  const __m512d threeHalves = _mm512_set1_pd(1.5);
  const __m512d halfX = _mm512_mul_pd(x, _mm512_set1_pd(0.5));
  __m512d y = _mm512_rsqrt14_pd(x);
  for (int it = 0; it < 2; ++it) {  // y ← y (3/2 − x y²/2)
    const __m512d hy2 = _mm512_mul_pd(_mm512_mul_pd(halfX, y), y);
    y = _mm512_mul_pd(y, _mm512_sub_pd(threeHalves, hy2));
  }
  const __mmask8 positive = _mm512_cmp_pd_mask(x, _mm512_setzero_pd(), _CMP_GT_OQ);
  return _mm512_maskz_mov_pd(positive, y);
}

// √x per lane for x ≥ 0, to a few ulp: vrsqrt14pd (14 bits), one Newton step for 1/√x (~28
// bits), then one Newton step for √x itself using that reciprocal (~53 bits). x = 0 gives 0
// (the reciprocal is taken of max(x, 1e-300), a normal double).
inline __m512d sqrtLanes(__m512d x) {
  const __m512d xc = _mm512_max_pd(x, _mm512_set1_pd(1e-300));
  const __m512d halfX = _mm512_mul_pd(xc, _mm512_set1_pd(0.5));
  __m512d y = _mm512_rsqrt14_pd(xc);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(_mm512_mul_pd(halfX, y), y, _mm512_set1_pd(1.5)));
  const __m512d r0 = _mm512_mul_pd(x, y);                    // √x (1 + O(2⁻²⁸))
  const __m512d e = _mm512_fnmadd_pd(r0, r0, x);              // x − r0²
  return _mm512_fmadd_pd(_mm512_mul_pd(y, _mm512_set1_pd(0.5)), e, r0);  // r0 + e / (2 r0)
}

// φ, a = φ′/x and e = a′/x for 8 squared distances (kernels.h conventions).
struct RadialLanes {
  __m512d phi, a, e;
};

template <KernelType T>
inline RadialLanes radialLanes(__m512d x2, double r) {
  RadialLanes o;
  const double r2 = r * r, r4 = r2 * r2;
  if constexpr (T == KernelType::Cubic) {
    const __m512d y = invSqrt(x2);
    const __m512d x = _mm512_mul_pd(x2, y);
    o.phi = _mm512_mul_pd(x2, x);
    o.a = _mm512_mul_pd(_mm512_set1_pd(3.0), x);
    o.e = _mm512_mul_pd(_mm512_set1_pd(3.0), y);
  } else if constexpr (T == KernelType::Gaussian) {
    const __m512d t = _mm512_mul_pd(x2, _mm512_set1_pd(-1.0 / r2));
    // Beyond x²/r² = 745.2 exp(−x²/r²) is 0 in double precision, but pexp clamps its argument and
    // returns about 1e-308, which far away (‖d‖ ≥ 1e100) would multiply ‖d‖² into garbage.
    const __mmask8 reach = _mm512_cmp_pd_mask(t, _mm512_set1_pd(-745.2), _CMP_GE_OQ);
    o.phi = _mm512_maskz_mov_pd(reach, Eigen::internal::pexp<Eigen::internal::Packet8d>(t));
    o.a = _mm512_mul_pd(o.phi, _mm512_set1_pd(-2.0 / r2));
    o.e = _mm512_mul_pd(o.phi, _mm512_set1_pd(4.0 / r4));
  } else if constexpr (T == KernelType::Wendland) {
    const __m512d y = invSqrt(x2);
    const __m512d s = _mm512_mul_pd(_mm512_mul_pd(x2, y), _mm512_set1_pd(1.0 / r));
    const __m512d u = _mm512_max_pd(_mm512_sub_pd(_mm512_set1_pd(1.0), s), _mm512_setzero_pd());
    const __m512d u2 = _mm512_mul_pd(u, u);
    // Lanes outside the support get exact zeros: where x² overflowed to inf, s is NaN (inf · 0
    // in invSqrt) and u = 0 (max takes the second operand), and 0 · NaN would poison the sum.
    const __mmask8 inside = _mm512_cmp_pd_mask(u, _mm512_setzero_pd(), _CMP_GT_OQ);
    o.phi = _mm512_maskz_mov_pd(
        inside, _mm512_mul_pd(_mm512_mul_pd(u2, u2), _mm512_fmadd_pd(_mm512_set1_pd(4.0), s, _mm512_set1_pd(1.0))));
    o.a = _mm512_mul_pd(_mm512_mul_pd(u2, u), _mm512_set1_pd(-20.0 / r2));
    o.e = _mm512_maskz_mov_pd(inside, _mm512_mul_pd(_mm512_mul_pd(u2, y), _mm512_set1_pd(60.0 / (r2 * r))));
  } else if constexpr (T == KernelType::Multiquadric) {
    const __m512d q = _mm512_fmadd_pd(x2, _mm512_set1_pd(1.0 / r2), _mm512_set1_pd(1.0));
    const __m512d y = invSqrt(q);  // 1/φ
    o.phi = _mm512_mul_pd(q, y);
    o.a = _mm512_mul_pd(y, _mm512_set1_pd(1.0 / r2));
    o.e = _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(y, y), y), _mm512_set1_pd(-1.0 / r4));
  } else if constexpr (T == KernelType::InverseMultiquadric) {
    const __m512d q = _mm512_fmadd_pd(x2, _mm512_set1_pd(1.0 / r2), _mm512_set1_pd(1.0));
    // q = inf (‖d‖² overflowed): φ and its factors are 0; invSqrt would give inf · 0 = NaN.
    const __mmask8 finite = _mm512_cmp_pd_mask(q, _mm512_set1_pd(std::numeric_limits<double>::max()), _CMP_LE_OQ);
    o.phi = _mm512_maskz_mov_pd(finite, invSqrt(q));
    const __m512d p3 = _mm512_mul_pd(_mm512_mul_pd(o.phi, o.phi), o.phi);
    o.a = _mm512_mul_pd(p3, _mm512_set1_pd(-1.0 / r2));
    o.e = _mm512_mul_pd(_mm512_mul_pd(p3, _mm512_mul_pd(o.phi, o.phi)), _mm512_set1_pd(3.0 / r4));
  } else {  // Polyharmonic: x⁴ ln x with ln x = ½ ln x²; exact 0 limits at x² = 0
    const __mmask8 positive = _mm512_cmp_pd_mask(x2, _mm512_setzero_pd(), _CMP_GT_OQ);
    const __m512d lx = _mm512_mul_pd(_mm512_set1_pd(0.5), Eigen::internal::plog<Eigen::internal::Packet8d>(x2));
    o.phi = _mm512_maskz_mov_pd(positive, _mm512_mul_pd(_mm512_mul_pd(x2, x2), lx));
    o.a = _mm512_maskz_mov_pd(positive, _mm512_mul_pd(x2, _mm512_fmadd_pd(_mm512_set1_pd(4.0), lx, _mm512_set1_pd(1.0))));
    o.e = _mm512_maskz_mov_pd(positive, _mm512_fmadd_pd(_mm512_set1_pd(8.0), lx, _mm512_set1_pd(6.0)));
  }
  return o;
}

// f (and ∇f into g when WantG) at x over `padded` centres (multiple of 8). c[k]: coordinate k
// of the centres, al: α, bc[k]: βₖ (unused when !Beta). Padding centres have zero coefficients.
template <int Dim, KernelType T, bool Beta, bool WantG>
inline double fusedSum(const double* x, double r, const double* const* c, const double* al,
                       const double* const* bc, int padded, double* g) {
  __m512d accF = _mm512_setzero_pd();
  __m512d accG[Dim];
  for (int k = 0; k < Dim; ++k) accG[k] = _mm512_setzero_pd();
  __m512d xs[Dim];
  for (int k = 0; k < Dim; ++k) xs[k] = _mm512_set1_pd(x[k]);
  for (int j = 0; j < padded; j += 8) {
    __m512d d[Dim];
    __m512d x2 = _mm512_setzero_pd();
    for (int k = 0; k < Dim; ++k) {
      d[k] = _mm512_sub_pd(xs[k], _mm512_loadu_pd(c[k] + j));
      x2 = _mm512_fmadd_pd(d[k], d[k], x2);
    }
    const RadialLanes rl = radialLanes<T>(x2, r);
    const __m512d alpha = _mm512_loadu_pd(al + j);
    accF = _mm512_fmadd_pd(alpha, rl.phi, accF);
    if constexpr (Beta) {
      __m512d b[Dim];
      __m512d db = _mm512_setzero_pd();
      for (int k = 0; k < Dim; ++k) {
        b[k] = _mm512_loadu_pd(bc[k] + j);
        db = _mm512_fmadd_pd(b[k], d[k], db);
      }
      accF = _mm512_fnmadd_pd(rl.a, db, accF);  // − a (β·d)
      if constexpr (WantG) {
        const __m512d edb = _mm512_mul_pd(rl.e, db);
        for (int k = 0; k < Dim; ++k) {
          // a (α dₖ − βₖ) − e (β·d) dₖ
          const __m512d t = _mm512_fmsub_pd(alpha, d[k], b[k]);
          accG[k] = _mm512_fnmadd_pd(edb, d[k], _mm512_fmadd_pd(rl.a, t, accG[k]));
        }
      }
    } else if constexpr (WantG) {
      const __m512d aa = _mm512_mul_pd(rl.a, alpha);
      for (int k = 0; k < Dim; ++k) accG[k] = _mm512_fmadd_pd(aa, d[k], accG[k]);
    }
  }
  if constexpr (WantG)
    for (int k = 0; k < Dim; ++k) g[k] = _mm512_reduce_add_pd(accG[k]);
  return _mm512_reduce_add_pd(accF);
}

}  // namespace hermite::detail

#pragma GCC diagnostic pop

#endif  // __AVX512F__
