#include "core/rbf/cholesky_condition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hermite {

namespace {

using Index = Eigen::Index;
using ConstMap = Eigen::Map<const Eigen::VectorXd>;

// The estimator's vectors (n each), reused from call to call on each thread.
struct EstimateBuffers {
  std::vector<double> v, alt, sign, oldSign;
  void resize(Index n) {
    if (static_cast<Index>(v.size()) >= n) return;
    for (std::vector<double>* b : {&v, &alt, &sign, &oldSign}) b->resize(static_cast<std::size_t>(n));
  }
};

EstimateBuffers& estimateBuffers() {
  thread_local EstimateBuffers buffers;
  return buffers;
}

// x ← L⁻¹x for x whose entries above row j0 are zero (they stay zero): column-oriented, one
// axpy per column of L.
void forwardFrom(const double* L, Index n, Index ld, double* x, Index j0) {
  for (Index j = j0; j < n; ++j) {
    const double* c = L + j * ld;
    const double w = x[j] / c[j];
    x[j] = w;
    for (Index i = j + 1; i < n; ++i) x[i] -= w * c[i];
  }
}

// x ← L⁻¹x and y ← L⁻¹y in one pass over L.
void forwardTwo(const double* L, Index n, Index ld, double* x, double* y) {
  for (Index j = 0; j < n; ++j) {
    const double* c = L + j * ld;
    const double wx = x[j] / c[j], wy = y[j] / c[j];
    x[j] = wx;
    y[j] = wy;
    for (Index i = j + 1; i < n; ++i) {
      x[i] -= wx * c[i];
      y[i] -= wy * c[i];
    }
  }
}

// x ← L⁻ᵀx: row-oriented on Lᵀ, one dot product with a column of L per entry.
void backward(const double* L, Index n, Index ld, double* x) {
  for (Index j = n - 1; j >= 0; --j) {
    const double* c = L + j * ld;
    const Index len = n - j - 1;
    x[j] = (x[j] - ConstMap(c + j + 1, len).dot(ConstMap(x + j + 1, len))) / c[j];
  }
}

// x ← L⁻ᵀx and y ← L⁻ᵀy in one pass over L.
void backwardTwo(const double* L, Index n, Index ld, double* x, double* y) {
  for (Index j = n - 1; j >= 0; --j) {
    const double* c = L + j * ld;
    const Index len = n - j - 1;
    const ConstMap col(c + j + 1, len);
    x[j] = (x[j] - col.dot(ConstMap(x + j + 1, len))) / c[j];
    y[j] = (y[j] - col.dot(ConstMap(y + j + 1, len))) / c[j];
  }
}

double oneNorm(const double* x, Index n) { return ConstMap(x, n).lpNorm<1>(); }

// Index of the first entry of largest magnitude.
Index argMaxAbs(const double* x, Index n) {
  Index best = 0;
  ConstMap(x, n).cwiseAbs().maxCoeff(&best);
  return best;
}

// s ← sign(v) (+1 for zero), as Eigen's rcond_compute_sign for real vectors.
void signOf(const double* v, Index n, double* s) {
  for (Index i = 0; i < n; ++i) s[i] = v[i] < 0 ? -1.0 : 1.0;
}

}  // namespace

double choleskyInverseNormEstimate(const double* L, Index n, Index ld) {
  if (n <= 0) return 0;
  EstimateBuffers& buf = estimateBuffers();
  buf.resize(n);
  double *v = buf.v.data(), *alt = buf.alt.data(), *sign = buf.sign.data(), *oldSign = buf.oldSign.data();
  // A⁻¹(e/n) and the alternating vector's A⁻¹x, together.
  double alternating = 1;
  for (Index i = 0; i < n; ++i) {
    v[i] = 1.0 / double(n);
    alt[i] = n > 1 ? alternating * (1.0 + double(i) / double(n - 1)) : 1.0;
    alternating = -alternating;
  }
  forwardTwo(L, n, ld, v, alt);
  backwardTwo(L, n, ld, v, alt);
  double lower = oneNorm(v, n);
  if (n == 1) return lower;
  double oldLower = lower;
  Index oldIndex = -1;
  for (int k = 0; k < 4; ++k) {
    signOf(v, n, sign);
    if (k > 0 && std::equal(sign, sign + n, oldSign)) break;  // stagnated
    std::copy(sign, sign + n, v);  // A⁻ᵀ sign(v) = A⁻¹ sign(v): A is symmetric
    forwardFrom(L, n, ld, v, 0);
    backward(L, n, ld, v);
    const Index j = argMaxAbs(v, n);
    if (j == oldIndex) break;
    std::fill(v, v + n, 0.0);  // v ← A⁻¹eⱼ
    v[j] = 1;
    forwardFrom(L, n, ld, v, j);
    backward(L, n, ld, v);
    lower = oneNorm(v, n);
    if (lower <= oldLower) break;  // Eigen keeps this last, smaller bound
    std::copy(sign, sign + n, oldSign);
    oldIndex = j;
    oldLower = lower;
  }
  const double alternate = 2 * oneNorm(alt, n) / (3 * double(n));
  return std::max(lower, alternate);
}

double choleskyReciprocalCondition(double aNorm, const double* L, Index n, Index ld) {
  if (n == 0) return std::numeric_limits<double>::infinity();
  if (aNorm == 0) return 0;
  if (n == 1) return 1;
  const double inverseNorm = choleskyInverseNormEstimate(L, n, ld);
  return inverseNorm == 0 ? 0 : (1.0 / inverseNorm) / aNorm;
}

}  // namespace hermite
