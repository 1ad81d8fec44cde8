#include "core/rbf/cholesky_condition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace hermite {

namespace {

using Index = Eigen::Index;
using ConstMap = Eigen::Map<const Eigen::VectorXd>;

// Factors up to this size get the row copy and the solves below; above it the copy's strided
// writes leave L1 and Eigen's blocked triangular solves are faster (measured at n = 92–200,
// docs/performance.md).
constexpr Index kRowCopyUpTo = 120;

// The estimator's vectors (n each), the reciprocals of L's diagonal, and L's rows, reused from
// call to call on each thread.
struct EstimateBuffers {
  std::vector<double> v, alt, sign, oldSign, invDiagonal;
  std::vector<double> rows;  // n × n, row j of L contiguous at j·n (entries 0..j)
  void resize(Index n) {
    if (static_cast<Index>(v.size()) < n)
      for (std::vector<double>* b : {&v, &alt, &sign, &oldSign, &invDiagonal}) b->resize(static_cast<std::size_t>(n));
    const Index copied = std::min(n, kRowCopyUpTo);
    if (static_cast<Index>(rows.size()) < copied * copied) rows.resize(static_cast<std::size_t>(copied * copied));
  }
};

EstimateBuffers& estimateBuffers() {
  thread_local EstimateBuffers buffers;
  return buffers;
}

// The factor as the solves read it: columns of L for the forward substitution, rows of L (the
// columns of Lᵀ) for the backward one, so that both are column-oriented — an axpy per column,
// no dot-product reductions, whose latency dominates at the local fits' usual 30–120 unknowns.
struct Factor {
  const double* L;     // column j at L + j·ld
  Index n, ld;
  const double* rows;  // row j at rows + j·n; null: not copied
  const double* inv;   // 1 / L(j, j)
};

using FactorMap = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using VectorMap = Eigen::Map<Eigen::VectorXd>;

// Columns per step of the substitutions below: each step reads and writes the entries of x past
// its columns once for all kStep of them, where a column at a time reads and writes them once per
// column. Each entry still takes the same subtractions in the same order, so the result is the
// same bit for bit.
constexpr int kStep = 4;

// The forward step over columns j..j+K−1 of L, on V vectors xs[v]: the diagonal block one column
// at a time, then the entries below it.
template <int K, int V>
void forwardStep(const Factor& f, double* const* xs, Index j) {
  const double* c[K];
  double w[V][K];
  for (int a = 0; a < K; ++a) {
    c[a] = f.L + (j + a) * f.ld;
    for (int v = 0; v < V; ++v) {
      double* x = xs[v];
      w[v][a] = x[j + a] * f.inv[j + a];
      x[j + a] = w[v][a];
      for (int b = a + 1; b < K; ++b) x[j + b] -= w[v][a] * c[a][j + b];
    }
  }
  for (int v = 0; v < V; ++v) {
    double* x = xs[v];
    for (Index i = j + K; i < f.n; ++i) {
      double s = x[i];
      for (int a = 0; a < K; ++a) s -= w[v][a] * c[a][i];
      x[i] = s;
    }
  }
}

// The backward step over rows j, j−1, …, j−K+1 of L (columns of Lᵀ, from the row copy).
template <int K, int V>
void backwardStep(const Factor& f, double* const* xs, Index j) {
  const double* r[K];
  double w[V][K];
  for (int a = 0; a < K; ++a) {
    r[a] = f.rows + (j - a) * f.n;
    for (int v = 0; v < V; ++v) {
      double* x = xs[v];
      w[v][a] = x[j - a] * f.inv[j - a];
      x[j - a] = w[v][a];
      for (int b = a + 1; b < K; ++b) x[j - b] -= w[v][a] * r[a][j - b];
    }
  }
  for (int v = 0; v < V; ++v) {
    double* x = xs[v];
    for (Index i = 0; i <= j - K; ++i) {
      double s = x[i];
      for (int a = 0; a < K; ++a) s -= w[v][a] * r[a][i];
      x[i] = s;
    }
  }
}

// xs[v] ← L⁻¹xs[v] for vectors whose entries above row j0 are zero (they stay zero).
template <int V>
void forward(const Factor& f, double* const* xs, Index j0) {
  Index j = j0;
  for (; j + kStep <= f.n; j += kStep) forwardStep<kStep, V>(f, xs, j);
  for (; j < f.n; ++j) forwardStep<1, V>(f, xs, j);
}

// xs[v] ← L⁻ᵀxs[v].
template <int V>
void backwardRows(const Factor& f, double* const* xs) {
  Index j = f.n - 1;
  for (; j + 1 >= kStep; j -= kStep) backwardStep<kStep, V>(f, xs, j);
  for (; j >= 0; --j) backwardStep<1, V>(f, xs, j);
}

// x ← L⁻¹x for x whose entries above row j0 are zero (they stay zero).
void forwardFrom(const Factor& f, double* x, Index j0) {
  if (!f.rows) {  // large: Eigen's blocked solve on the trailing block
    const Index k = f.n - j0;
    const FactorMap L(f.L + j0 * f.ld + j0, k, k, Eigen::OuterStride<>(f.ld));
    VectorMap tail(x + j0, k);
    L.triangularView<Eigen::Lower>().solveInPlace(tail);
    return;
  }
  forward<1>(f, &x, j0);
}

// x ← L⁻¹x and y ← L⁻¹y in one pass over L.
void forwardTwo(const Factor& f, double* x, double* y) {
  if (!f.rows) {
    forwardFrom(f, x, 0);
    forwardFrom(f, y, 0);
    return;
  }
  double* const xs[2] = {x, y};
  forward<2>(f, xs, 0);
}

// x ← L⁻ᵀx: column j of Lᵀ is row j of L (from the copy).
void backward(const Factor& f, double* x) {
  if (!f.rows) {
    const FactorMap L(f.L, f.n, f.n, Eigen::OuterStride<>(f.ld));
    VectorMap v(x, f.n);
    L.triangularView<Eigen::Lower>().transpose().solveInPlace(v);
    return;
  }
  backwardRows<1>(f, &x);
}

// x ← L⁻ᵀx and y ← L⁻ᵀy in one pass over L.
void backwardTwo(const Factor& f, double* x, double* y) {
  if (!f.rows) {
    backward(f, x);
    backward(f, y);
    return;
  }
  double* const xs[2] = {x, y};
  backwardRows<2>(f, xs);
}

// The reciprocals of L's diagonal and, for small factors, the rows of L into the buffers.
Factor prepareFactor(const double* L, Index n, Index ld, EstimateBuffers& buf) {
  const bool copyRows = n <= kRowCopyUpTo;
  double* rows = copyRows ? buf.rows.data() : nullptr;
  for (Index j = 0; j < n; ++j) {
    const double* c = L + j * ld;
    buf.invDiagonal[static_cast<std::size_t>(j)] = 1.0 / c[j];
    if (copyRows)
      for (Index i = j; i < n; ++i) rows[i * n + j] = c[i];
  }
  return Factor{L, n, ld, rows, buf.invDiagonal.data()};
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
  const Factor f = prepareFactor(L, n, ld, buf);
  double *v = buf.v.data(), *alt = buf.alt.data(), *sign = buf.sign.data(), *oldSign = buf.oldSign.data();
  // A⁻¹(e/n) and the alternating vector's A⁻¹x, together.
  double alternating = 1;
  for (Index i = 0; i < n; ++i) {
    v[i] = 1.0 / double(n);
    alt[i] = n > 1 ? alternating * (1.0 + double(i) / double(n - 1)) : 1.0;
    alternating = -alternating;
  }
  forwardTwo(f, v, alt);
  backwardTwo(f, v, alt);
  double lower = oneNorm(v, n);
  if (n == 1) return lower;
  double oldLower = lower;
  Index oldIndex = -1;
  for (int k = 0; k < 4; ++k) {
    signOf(v, n, sign);
    if (k > 0 && std::equal(sign, sign + n, oldSign)) break;  // stagnated
    std::copy(sign, sign + n, v);  // A⁻ᵀ sign(v) = A⁻¹ sign(v): A is symmetric
    forwardFrom(f, v, 0);
    backward(f, v);
    const Index j = argMaxAbs(v, n);
    if (j == oldIndex) break;
    std::fill(v, v + n, 0.0);  // v ← A⁻¹eⱼ
    v[j] = 1;
    forwardFrom(f, v, j);
    backward(f, v);
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
