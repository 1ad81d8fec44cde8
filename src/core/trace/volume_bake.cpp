#include "core/trace/volume_bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/rbf/polynomial.h"
#include "core/rbf/radial_sum.h"

#include "core/rbf/radial_sum_avx512.h"

namespace hermite {

namespace {

// What a no-data sample whose f is 0 in float is baked as: positive, and far above float's
// smallest normal (1.2e-38), so trilinear weights (the largest of the eight is ≥ 1/8) never
// flush it to zero.
constexpr float kNoDataFloor = 1e-30f;

// Fills lipschitz, centreValue and mayContainZero of a grid whose bounds, count and size are set.
void fillBrickGrid(const ImplicitField<3>& field, BrickGrid& grid) {
  const int n = grid.brickCount();
  grid.lipschitz.assign(n, 0.0);
  grid.centerValue.assign(n, 0.0);
  grid.mayContainZero.assign(n, 1);
  Points<3> centres(3, n);
  std::vector<double> halfDiagonal(n);
#pragma omp parallel for schedule(dynamic, 4)
  for (int b = 0; b < n; ++b) {
    const int bx = b % grid.count.x(), by = (b / grid.count.x()) % grid.count.y(),
              bz = b / (grid.count.x() * grid.count.y());
    const Box<3> box = grid.brickBox(bx, by, bz);
    grid.lipschitz[b] = field.lipschitzBound(box);
    centres.col(b) = box.center();
    halfDiagonal[b] = 0.5 * box.extent().norm();
  }
  Eigen::VectorXd f;
  field.evaluateBatch(centres, f);
  for (int b = 0; b < n; ++b) {
    grid.centerValue[b] = f(b);
    // |f(x) − f(c)| ≤ L‖x − c‖ ≤ L·halfDiagonal in the brick, so |f(c)| above that proves no
    // zero. The relative margin absorbs rounding of f(c) and of the bound; NaN never culls.
    const double reach = grid.lipschitz[b] * halfDiagonal[b];
    const bool proven = std::abs(f(b)) > reach * (1.0 + 1e-9) + 1e-300;
    grid.mayContainZero[b] = proven ? 0 : 1;
  }
}


#if defined(__AVX512F__)
constexpr int kBlocks = 8;  // vectors of 8 x-samples per chunk of a row (8 accumulators)

// What the cubic grid bake reads per row: the centres, α and β as separate arrays (n each; β
// zero without gradients), the row's x-samples (blocks·8, the last repeated past R − 1) and the
// polynomial p(x − po).
struct CubicRows {
  int n = 0, R = 0, blocks = 0;
  std::vector<double> cx, cy, cz, al, bx, by, bz;
  std::vector<double> xs;
  Polynomial poly = Polynomial::None;
  const Eigen::VectorXd* pc = nullptr;
  Vec<3> po = Vec<3>::Zero();
};

// The arrays of CubicRows for a bake of R³ samples from bounds.lo with spacing h.
CubicRows cubicRows(const RadialSum<3>& rs, const Box<3>& bounds, int R, const Vec<3>& h) {
  CubicRows g;
  g.n = int(rs.centres().cols());
  g.R = R;
  const bool beta = rs.hasBeta();
  for (std::vector<double>* v : {&g.cx, &g.cy, &g.cz, &g.al, &g.bx, &g.by, &g.bz}) v->assign(g.n, 0.0);
  for (int j = 0; j < g.n; ++j) {
    g.cx[j] = rs.centres()(0, j);
    g.cy[j] = rs.centres()(1, j);
    g.cz[j] = rs.centres()(2, j);
    g.al[j] = rs.alpha()(j);
    if (beta) {
      g.bx[j] = rs.beta()(0, j);
      g.by[j] = rs.beta()(1, j);
      g.bz[j] = rs.beta()(2, j);
    }
  }
  g.blocks = (R + 7) / 8;
  g.xs.resize(std::size_t(g.blocks) * 8);
  for (int i = 0; i < g.blocks * 8; ++i) g.xs[i] = bounds.lo.x() + h.x() * std::min(i, R - 1);
  g.poly = rs.polynomial();
  g.pc = &rs.poly();
  g.po = rs.polyOrigin();
  return g;
}

// dst[i] = acc's lane for x-sample i plus the polynomial at (xs[i], y, z), for the nb vectors
// from block b0 and i < R.
void storeCubicChunk(const CubicRows& g, int b0, int nb, double y, double z, const __m512d* acc, float* dst) {
  const Eigen::VectorXd& pc = *g.pc;
  for (int q = 0; q < nb; ++q) {
    alignas(64) double v[8];
    _mm512_store_pd(v, acc[q]);
    for (int l = 0; l < 8; ++l) {
      const int i = (b0 + q) * 8 + l;
      if (i >= g.R) break;
      const double px = g.xs[i] - g.po(0), py = y - g.po(1), pz = z - g.po(2);
      const double p = g.poly == Polynomial::Linear ? pc(0) + pc(1) * px + pc(2) * py + pc(3) * pz
                       : g.poly == Polynomial::None ? 0.0
                                                    : evaluatePolynomial<3>(g.poly, pc, Vec<3>(px, py, pz), nullptr, nullptr);
      dst[i] = float(v[l] + p);
    }
  }
}

// One chunk of a row at (y, z): up to kBlocks vectors of x-samples from block b0, summed over
// every centre. Per pair: f += r (α r² − 3 β·d), with dy² + dz² and βy dy + βz dz hoisted.
void bakeCubicChunk(const CubicRows& g, int b0, double y, double z, float* dst) {
  const int nb = std::min(kBlocks, g.blocks - b0);
  __m512d acc[kBlocks], xv[kBlocks];
  for (int q = 0; q < kBlocks; ++q) {
    acc[q] = _mm512_setzero_pd();
    xv[q] = q < nb ? _mm512_loadu_pd(&g.xs[std::size_t(b0 + q) * 8]) : _mm512_setzero_pd();
  }
  for (int c = 0; c < g.n; ++c) {
    const double dy = y - g.cy[c], dz = z - g.cz[c];
    const __m512d C = _mm512_set1_pd(dy * dy + dz * dz);
    const __m512d B = _mm512_set1_pd(-3.0 * (g.by[c] * dy + g.bz[c] * dz));
    const __m512d X = _mm512_set1_pd(g.cx[c]);
    const __m512d A = _mm512_set1_pd(g.al[c]);
    const __m512d BX = _mm512_set1_pd(-3.0 * g.bx[c]);
    auto pair = [&](int q) {
      const __m512d dx = _mm512_sub_pd(xv[q], X);
      const __m512d r2 = _mm512_fmadd_pd(dx, dx, C);
      const __m512d r = detail::sqrtLanes(r2);
      // α r² − 3 β·d
      const __m512d t = _mm512_fmadd_pd(A, r2, _mm512_fmadd_pd(BX, dx, B));
      acc[q] = _mm512_fmadd_pd(r, t, acc[q]);
    };
    if (nb == kBlocks) {
#pragma GCC unroll 8
      for (int q = 0; q < kBlocks; ++q) pair(q);
    } else {
      for (int q = 0; q < nb; ++q) pair(q);
    }
  }
  storeCubicChunk(g, b0, nb, y, z, acc, dst);
}

// Grid bake of a cubic RadialSum<3> (HRBF or plain RBF, φ = x³, a = φ′/x = 3x): row by row
// along x, 8 x-samples per vector, with what depends only on the row and the centre hoisted out
// of the x loop — the structure evaluateBatch cannot see. Threaded over rows. False (nothing
// written) for other fields.
bool bakeCubicRadialSum(const ImplicitField<3>& field, const Box<3>& bounds, int R, const Vec<3>& h, float* out,
                        const CancelToken* cancel) {
  const RadialSum<3>* rs = field.asRadialSum();
  if (rs == nullptr || rs->kernel().type != KernelType::Cubic) return false;
  const CubicRows g = cubicRows(*rs, bounds, R, h);
  const std::size_t plane = std::size_t(R) * R;
#pragma omp parallel for schedule(dynamic, 16)
  for (int row = 0; row < R * R; ++row) {
    if (cancel && cancel->cancelled()) continue;  // the caller throws after the loop
    const int j = row % R, k = row / R;
    const double y = bounds.lo.y() + h.y() * j, z = bounds.lo.z() + h.z() * k;
    float* dst = out + plane * k + std::size_t(R) * j;
    for (int b0 = 0; b0 < g.blocks; b0 += kBlocks) bakeCubicChunk(g, b0, y, z, dst);
  }
  return true;
}

#else
bool bakeCubicRadialSum(const ImplicitField<3>&, const Box<3>&, int, const Vec<3>&, float*, const CancelToken*) {
  return false;
}
#endif

// X = the grid points of z-planes k0 … k1 − 1 (3 × R²·(k1 − k0)), x fastest, then y, then z.
void slabPoints(const Box<3>& bounds, int R, const Vec<3>& h, int k0, int k1, Points<3>& X) {
  const std::size_t plane = std::size_t(R) * R;
  X.resize(3, Eigen::Index(plane) * (k1 - k0));
#pragma omp parallel for schedule(static)
  for (int k = k0; k < k1; ++k) {
    const double z = bounds.lo.z() + h.z() * k;
    for (int j = 0; j < R; ++j) {
      const double y = bounds.lo.y() + h.y() * j;
      Eigen::Index col = Eigen::Index(plane) * (k - k0) + Eigen::Index(R) * j;
      for (int i = 0; i < R; ++i, ++col) X.col(col) = Vec<3>(bounds.lo.x() + h.x() * i, y, z);
    }
  }
}

// out[q] = f(X.col(q)) as float, for every column of X, and noData[q] = 1 where a zero of f would
// not be surface (validOnZeroSet; noData null: the field has data everywhere); f and valid are
// scratch kept between slabs.
void storeSlabValues(const ImplicitField<3>& field, const Points<3>& X, Eigen::VectorXd& f, std::vector<char>& valid,
                     float* out, std::uint8_t* noData) {
  const Eigen::Index m = X.cols();
  if (!noData) {
    field.evaluateBatch(X, f);
#pragma omp parallel for schedule(static)
    for (Eigen::Index q = 0; q < m; ++q) out[q] = float(f(q));
    return;
  }
  // No data keeps f's sign (docs/maths.md, "No data"): f is continuous across the edge of the
  // data, so no zero appears there, and the tracer passes the zeros it meets where the samples
  // say they are no surface (an open scan's interpolant closing it, seen through its opening) —
  // by the zero-set test the mesher's vertices and the hit refinement take. An exact 0
  // is stored as kNoDataFloor: the march takes f = 0 as a zero to check, and a flat field's no
  // data is often exactly 0 (a compact kernel beyond r of every sample).
  field.evaluateBatch(X, f);
  field.validOnZeroSetBatch(X, valid);
#pragma omp parallel for schedule(static)
  for (Eigen::Index q = 0; q < m; ++q) {
    const bool has = valid[std::size_t(q)] != 0;
    noData[q] = has ? 0 : 1;
    const float v = float(f(q));
    out[q] = has || v != 0 ? v : kNoDataFloor;
  }
}

// The R³ samples through evaluateBatch (any field), in slabs of whole z-planes, ~64k points
// each: large enough for evaluateBatch's threads, small enough to keep X (3 × points doubles)
// in cache-friendly sizes. noData as storeSlabValues takes it, R³ entries.
void bakeBatched(const ImplicitField<3>& field, const Box<3>& bounds, int R, const Vec<3>& h, float* out,
                 std::uint8_t* noData, const CancelToken* cancel) {
  const std::size_t plane = std::size_t(R) * R;
  const int planesPerSlab = std::max<int>(1, int(65536 / plane));
  Points<3> X;
  Eigen::VectorXd f;
  std::vector<char> valid;
  for (int k0 = 0; k0 < R; k0 += planesPerSlab) {
    throwIfCancelled(cancel);
    const int k1 = std::min(R, k0 + planesPerSlab);
    slabPoints(bounds, R, h, k0, k1, X);
    storeSlabValues(field, X, f, valid, out + plane * k0, noData ? noData + plane * k0 : nullptr);
  }
}

// Throws InputError unless R ≥ 2, brick cells ≥ 1 and the bounds are finite with min < max.
void checkBakeArguments(const Box<3>& bounds, const VolumeBakeOptions& options) {
  const int R = options.resolution;
  const int C = options.brickCells;
  if (R < 2) throw InputError("volume bake: resolution must be ≥ 2 (got " + std::to_string(R) + ")");
  if (C < 1) throw InputError("volume bake: brick cells must be ≥ 1 (got " + std::to_string(C) + ")");
  if (!((bounds.hi - bounds.lo).array() > 0).all() || !bounds.lo.allFinite() || !bounds.hi.allFinite())
    throw InputError("volume bake: bounds must be finite with min < max");
}

// The bake's bricks of C cells per axis: Lipschitz bounds and centre values from the field,
// and each brick's least and greatest baked sample (its (C + 1)³ samples, fewer at the end).
void fillBakeBricks(const ImplicitField<3>& field, VolumeBake& bake) {
  const int R = bake.resolution, C = bake.brickCells;
  const std::size_t plane = std::size_t(R) * R;
  BrickGrid& grid = bake.bricks;
  grid.bounds = bake.bounds;
  const int perAxis = (R - 1 + C - 1) / C;
  grid.count = Eigen::Array3i::Constant(perAxis);
  grid.size = double(C) * bake.spacing();
  fillBrickGrid(field, grid);
  const int n = grid.brickCount();
  bake.brickMin.assign(n, 0.0f);
  bake.brickMax.assign(n, 0.0f);
#pragma omp parallel for schedule(static)
  for (int b = 0; b < n; ++b) {
    const int bx = b % perAxis, by = (b / perAxis) % perAxis, bz = b / (perAxis * perAxis);
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int k = bz * C; k <= std::min((bz + 1) * C, R - 1); ++k)
      for (int j = by * C; j <= std::min((by + 1) * C, R - 1); ++j) {
        const float* row = bake.values.data() + plane * k + std::size_t(R) * j;
        for (int i = bx * C; i <= std::min((bx + 1) * C, R - 1); ++i) {
          lo = std::min(lo, row[i]);
          hi = std::max(hi, row[i]);
        }
      }
    bake.brickMin[b] = lo;
    bake.brickMax[b] = hi;
  }
}
}  // namespace

Box<3> BrickGrid::brickBox(int bx, int by, int bz) const {
  const Vec<3> b(bx, by, bz);
  Box<3> box;
  box.lo = bounds.lo + size.cwiseProduct(b);
  box.hi = (bounds.lo + size.cwiseProduct(b + Vec<3>::Ones())).cwiseMin(bounds.hi);
  // The last brick ends exactly at the bounds (no gap from rounding of lo + count·size).
  if (bx == count.x() - 1) box.hi.x() = bounds.hi.x();
  if (by == count.y() - 1) box.hi.y() = bounds.hi.y();
  if (bz == count.z() - 1) box.hi.z() = bounds.hi.z();
  return box;
}

Eigen::Array3i BrickGrid::locate(const Vec<3>& x) const {
  Eigen::Array3i b;
  for (int k = 0; k < 3; ++k) {
    const double q = std::floor((x(k) - bounds.lo(k)) / size(k));
    b(k) = int(std::clamp(q, 0.0, double(count(k) - 1)));
  }
  return b;
}

BrickGrid computeBrickGrid(const ImplicitField<3>& field, const Box<3>& bounds, const Eigen::Array3i& count) {
  if ((count < 1).any()) throw InputError("brick grid: need at least one brick per axis");
  if (!((bounds.hi - bounds.lo).array() > 0).all()) throw InputError("brick grid: empty bounds");
  BrickGrid grid;
  grid.bounds = bounds;
  grid.count = count;
  grid.size = bounds.extent().cwiseQuotient(count.cast<double>().matrix());
  fillBrickGrid(field, grid);
  return grid;
}

double VolumeBake::interpolate(const Vec<3>& x) const {
  const int R = resolution;
  const Vec<3> q = (x - bounds.lo).cwiseQuotient(spacing());
  int i0[3];
  double w[3];
  for (int k = 0; k < 3; ++k) {
    const double c = std::clamp(q(k), 0.0, double(R - 1));
    i0[k] = std::min(int(c), R - 2);
    w[k] = c - i0[k];
  }
  double f = 0;
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
    const double weight = (dx ? w[0] : 1 - w[0]) * (dy ? w[1] : 1 - w[1]) * (dz ? w[2] : 1 - w[2]);
    f += weight * value(i0[0] + dx, i0[1] + dy, i0[2] + dz);
  }
  return f;
}

VolumeBake bakeVolume(const ImplicitField<3>& field, const Box<3>& bounds, const VolumeBakeOptions& options) {
  checkBakeArguments(bounds, options);
  VolumeBake bake;
  bake.bounds = bounds;
  bake.resolution = options.resolution;
  bake.brickCells = options.brickCells;
  const int R = bake.resolution;
  bake.values.resize(std::size_t(R) * R * R);
  const Vec<3> h = bake.spacing();

  auto t0 = std::chrono::steady_clock::now();
  if (!field.everywhereValid()) bake.noData.resize(bake.values.size());
  if (!bakeCubicRadialSum(field, bounds, R, h, bake.values.data(), options.cancel))
    bakeBatched(field, bounds, R, h, bake.values.data(), bake.noData.empty() ? nullptr : bake.noData.data(),
                options.cancel);
  throwIfCancelled(options.cancel);
  bake.sampleMs = msSince(t0);

  t0 = std::chrono::steady_clock::now();
  fillBakeBricks(field, bake);
  bake.brickMs = msSince(t0);
  return bake;
}

}  // namespace hermite
