#include "core/pu/pu_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/errors.h"
#include "core/pu/pu_bump.h"
#include "core/pu/pu_near_field.h"

namespace hermite {

namespace {

using detail::bump;
using detail::kMaxBumpSlope;

// The median longest edge of the blended leaves' supports (frame units); 0 when none is blended.
template <class Leaf>
double medianSupportEdge(const std::vector<Leaf>& leaves) {
  std::vector<double> edges;
  for (const Leaf& l : leaves)
    if (l.blended) edges.push_back(l.support.extent().maxCoeff());
  if (edges.empty()) return 0.0;
  std::nth_element(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(edges.size() / 2), edges.end());
  return edges[edges.size() / 2];
}

}  // namespace

template <int Dim>
Similarity<Dim> composeSimilarity(const Similarity<Dim>& S, const Similarity<Dim>& T) {
  Similarity<Dim> out;
  out.q = S.q * T.q;
  out.R = S.R * T.R;
  out.t = S.q * (S.R * T.t) + S.t;
  return out;
}

template <int Dim>
PuModel<Dim>::PuModel(PuTree<Dim> tree, std::vector<Leaf> leaves, const PuOptions& options,
                      const Similarity<Dim>& frame, PuDataReach<Dim> dataReach)
    : tree_(std::move(tree)),
      leaves_(std::move(leaves)),
      options_(options),
      frame_(frame),
      dataReach_(std::move(dataReach)) {
  identityFrame_ = frame_.isIdentity();
  minFactor_ = std::numeric_limits<double>::infinity();
  for (const Leaf& l : leaves_)
    if (l.blended) minFactor_ = std::min(minFactor_, l.factor);
  if (!std::isfinite(minFactor_)) minFactor_ = 1.0;
  noData_ = tree_.nodes().empty() ? 1.0 : frame_.q * tree_.root().extent().norm();
  typicalSupport_ = medianSupportEdge(leaves_);
  buildReach();
}

template <int Dim>
void PuModel<Dim>::buildReach() {
  const auto& nodes = tree_.nodes();
  reach_.assign(nodes.size(), Box<Dim>{});
  allBlended_.assign(nodes.size(), 1);
  // Children come after their parent: a backward pass sees them first.
  for (int id = static_cast<int>(nodes.size()) - 1; id >= 0; --id) {
    const auto& nd = nodes[id];
    if (nd.firstChild < 0) {
      if (leaves_[nd.leaf].blended) {
        reach_[id] = leaves_[nd.leaf].support;
      } else {  // never blended: an empty reach
        allBlended_[static_cast<std::size_t>(id)] = 0;
        reach_[id].lo.setConstant(std::numeric_limits<double>::infinity());
        reach_[id].hi.setConstant(-std::numeric_limits<double>::infinity());
      }
    } else {
      Box<Dim> r = reach_[nd.firstChild];
      for (int ch = 1; ch < PuTree<Dim>::kChildren; ++ch) {
        r.lo = r.lo.cwiseMin(reach_[nd.firstChild + ch].lo);
        r.hi = r.hi.cwiseMax(reach_[nd.firstChild + ch].hi);
      }
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch)
        if (!allBlended_[static_cast<std::size_t>(nd.firstChild + ch)]) allBlended_[static_cast<std::size_t>(id)] = 0;
      reach_[id] = r;
    }
  }
}

template <int Dim>
template <class Accept>
bool PuModel<Dim>::anySupportAt(const Vec<Dim>& y, Accept&& accept) const {
  const auto& nodes = tree_.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    if (!reach_[id].contains(y)) continue;
    const auto& nd = nodes[id];
    if (nd.firstChild < 0) {
      if (accept(nd.leaf)) return true;
    } else {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    }
  }
  return false;
}

template <int Dim>
template <class F>
void PuModel<Dim>::forSupportsAt(const Vec<Dim>& y, F&& visit) const {
  anySupportAt(y, [&](int leaf) {
    visit(leaf);
    return false;  // every support
  });
}

template <int Dim>
template <class F>
void PuModel<Dim>::forSupportsTouching(const Box<Dim>& b, F&& visit) const {
  const auto& nodes = tree_.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    if (!boxesIntersect<Dim>(reach_[id], b)) continue;
    const auto& nd = nodes[id];
    if (nd.firstChild < 0) {
      visit(nd.leaf);
    } else {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    }
  }
}

template <int Dim>
double PuModel<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  return evaluateValid(x, g, H, nullptr);
}

template <int Dim>
double PuModel<Dim>::evaluateValid(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H, bool* valid) const {
  if (valid) *valid = true;
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  if (options_.blend == PuBlend::Hard) return leaves_[tree_.locateLeaf(y)].model.evaluate(x, g, H);
  const bool frozen[Dim] = {};
  const Vec<Dim>& yc = y;
  const bool needG = g != nullptr || H != nullptr;
  const bool needH = H != nullptr;
  // f = N/S with N = Σ wᵢfᵢ, S = Σ wᵢ; derivatives of N and S by the product rule.
  double S = 0, N = 0;
  Vec<Dim> gS = Vec<Dim>::Zero(), gN = Vec<Dim>::Zero();
  Mat<Dim> HS = Mat<Dim>::Zero(), HN = Mat<Dim>::Zero();
  const double invQ = 1.0 / frame_.q;
  forSupportsAt(yc, [&](int i) {
    const Leaf& leaf = leaves_[i];
    if (!leaf.support.contains(yc)) return;
    Vec<Dim> gw;
    Mat<Dim> Hw;
    const double w = bump<Dim>(leaf.support, yc, frozen, needG ? &gw : nullptr, needH ? &Hw : nullptr);
    if (w == 0.0) return;
    if (!identityFrame_) {
      // y = R⁻¹(x − t)/q: ∇ₓ = R∇_y/q, Hₓ = R H_y Rᵀ/q².
      if (needG) gw = invQ * (frame_.R * gw);
      if (needH) Hw = (invQ * invQ) * (frame_.R * Hw * frame_.R.transpose());
    }
    Vec<Dim> gi;
    Mat<Dim> Hi;
    const double fi = leaf.model.evaluate(x, needG ? &gi : nullptr, needH ? &Hi : nullptr);
    S += w;
    N += w * fi;
    if (needG) {
      gS += gw;
      gN += fi * gw + w * gi;
    }
    if (needH) {
      HS += Hw;
      HN += fi * Hw + gw * gi.transpose() + gi * gw.transpose() + w * Hi;
    }
  });
  if (!(S > 0)) return evaluateUncovered(x, y, g, H, valid);
  if (valid) *valid = dataReach_.reaches(tree_, y);
  const double f = N / S;
  if (needG) {
    const Vec<Dim> gf = (gN - f * gS) / S;
    if (g) *g = gf;
    if (needH) *H = (HN - gf * gS.transpose() - gS * gf.transpose() - f * HS) / S;
  }
  return f;
}

template <int Dim>
double PuModel<Dim>::evaluateUncovered(const Vec<Dim>& x, const Vec<Dim>& y, Vec<Dim>* g, Mat<Dim>* H,
                                       bool* valid) const {
  if (tree_.root().contains(y)) {
    const Leaf& own = leaves_[tree_.locateLeaf(y)];
    if (own.blended) {
      if (valid) *valid = dataReach_.reaches(tree_, y);
      return own.model.evaluate(x, g, H);
    }
  }
  if (valid) *valid = false;
  if (g) g->setZero();
  if (H) H->setZero();
  return noData_;
}

template <int Dim>
bool PuModel<Dim>::valid(const Vec<Dim>& x) const {
  return validNear(x, 0.0);
}

template <int Dim>
bool PuModel<Dim>::validNear(const Vec<Dim>& x, double margin) const {
  if (options_.blend == PuBlend::Hard) return true;
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  const bool frozen[Dim] = {};
  const bool reached =
      anySupportAt(y, [&](int i) { return bump<Dim>(leaves_[i].support, y, frozen, nullptr, nullptr) > 0; });
  return (reached || (tree_.root().contains(y) && leaves_[tree_.locateLeaf(y)].blended)) &&
         dataReach_.reaches(tree_, y, margin / frame_.q);
}

template <int Dim>
bool PuModel<Dim>::validOnZeroSet(const Vec<Dim>& x) const {
  if (options_.blend == PuBlend::Hard || dataReach_.empty()) return valid(x);
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  const double scale = std::min(1.0, options_.vertexReach / dataReach_.factor());
  return dataReach_.reaches(tree_, y, 0.0, scale) && valid(x);
}

template <int Dim>
bool PuModel<Dim>::coveredByData(const Box<Dim>& yb) const {
  const Box<Dim>& root = tree_.root();
  if (!((yb.lo.array() >= root.lo.array()).all() && (yb.hi.array() <= root.hi.array()).all())) return false;
  const auto& nodes = tree_.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    const auto& nd = nodes[id];
    if (!boxesIntersect<Dim>(nd.box, yb) || allBlended_[static_cast<std::size_t>(id)]) continue;
    if (nd.firstChild < 0) return false;  // a leaf without data meets yb
    for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
  }
  return true;
}

// f (and ∇f) for the smooth blend by runs of kRun consecutive columns of X: callers that care pass
// neighbouring points next to each other (the mesher's blocks and vertices), so a run's bounding
// box meets few supports; a run of scattered points (scatteredRun) goes point by point. A run
// looks its supports up once and evaluates each local fit at the run's points inside its support
// by the fit's vectorised batch loop (nested in this parallel loop, it runs on the calling
// thread). Per point the sums are the ones evaluateValid() forms — the same supports in the same
// order (depth first, as forSupportsAt), N = Σ wᵢ fᵢ, S = Σ wᵢ and their gradients — with each fᵢ
// rounded as the vectorised loop rounds it, whatever the other columns.
template <int Dim>
struct PuRunScratch {
  // 32 points: fewer than 64 waste fewer support tests, more than 16 share the tree walk (mesh
  // of 200 000 and 1 000 000 points, docs/performance.md).
  static constexpr Eigen::Index kRun = 32;
  Vec<Dim> y[kRun], gS[kRun], gN[kRun], gw[kRun];
  double yAxis[Dim][kRun];  // the same y, one array per axis, for the containment test
  double S[kRun], N[kRun], w[kRun];
  int members[kRun], inside[kRun];
  std::vector<int> leaves;
  Points<Dim> Xi, Gi;
  Eigen::VectorXd fi;
};

namespace {

// sc.inside[0..k) ← the run's points (of `count`) that `box` contains, ascending; returns k. The
// same test as Box::contains, without a branch per point: a run meets 10–30 supports and holds
// 3–4 of their points on average, so a branch per point mispredicts on most of them.
template <int Dim>
int runPointsInside(const Box<Dim>& box, Eigen::Index count, PuRunScratch<Dim>& sc) {
  unsigned char in[PuRunScratch<Dim>::kRun];
  for (Eigen::Index j = 0; j < count; ++j) {
    bool c = true;
    for (int d = 0; d < Dim; ++d) c &= (sc.yAxis[d][j] >= box.lo[d]) & (sc.yAxis[d][j] <= box.hi[d]);
    in[j] = c;
  }
  int k = 0;
  for (Eigen::Index j = 0; j < count; ++j) {
    sc.inside[k] = static_cast<int>(j);
    k += in[j];
  }
  return k;
}

}  // namespace

template <int Dim>
void PuModel<Dim>::evaluateRun(const Points<Dim>& X, Eigen::Index begin, Eigen::Index count, Eigen::VectorXd& f,
                               Points<Dim>* G, PuRunScratch<Dim>& sc) const {
  const bool frozen[Dim] = {};
  const double invQ = 1.0 / frame_.q;
  Box<Dim> bb{Vec<Dim>::Constant(std::numeric_limits<double>::infinity()),
              Vec<Dim>::Constant(-std::numeric_limits<double>::infinity())};
  for (Eigen::Index j = 0; j < count; ++j) {
    sc.y[j] = identityFrame_ ? Vec<Dim>(X.col(begin + j)) : frame_.applyInverse(X.col(begin + j));
    for (int d = 0; d < Dim; ++d) sc.yAxis[d][j] = sc.y[j][d];
    bb.lo = bb.lo.cwiseMin(sc.y[j]);
    bb.hi = bb.hi.cwiseMax(sc.y[j]);
    sc.S[j] = sc.N[j] = 0;
    sc.gS[j].setZero();
    sc.gN[j].setZero();
  }
  sc.leaves.clear();
  forSupportsTouching(bb, [&](int i) { sc.leaves.push_back(i); });
  for (int i : sc.leaves) {
    const Leaf& leaf = leaves_[i];
    int m = 0;
    const int inside = runPointsInside<Dim>(leaf.support, count, sc);
    for (int c = 0; c < inside; ++c) {
      const int j = sc.inside[c];
      const double wj = bump<Dim>(leaf.support, sc.y[j], frozen, G ? &sc.gw[m] : nullptr, nullptr);
      if (wj == 0.0) continue;
      if (G && !identityFrame_) sc.gw[m] = invQ * (frame_.R * sc.gw[m]);
      sc.w[m] = wj;
      sc.members[m++] = j;
    }
    if (m == 0) continue;
    sc.Xi.resize(Dim, m);
    for (int k = 0; k < m; ++k) sc.Xi.col(k) = X.col(begin + sc.members[k]);
    leaf.model.evaluateBatch(sc.Xi, sc.fi, G ? &sc.Gi : nullptr);
    for (int k = 0; k < m; ++k) {
      const int j = sc.members[k];
      sc.S[j] += sc.w[k];
      sc.N[j] += sc.w[k] * sc.fi[k];
      if (G) {
        sc.gS[j] += sc.gw[k];
        sc.gN[j] += sc.fi[k] * sc.gw[k] + sc.w[k] * sc.Gi.col(k);
      }
    }
  }
  for (Eigen::Index j = 0; j < count; ++j) {
    Vec<Dim> g;
    if (!(sc.S[j] > 0)) {
      f(begin + j) = evaluateUncovered(X.col(begin + j), sc.y[j], G ? &g : nullptr, nullptr, nullptr);
    } else {
      f(begin + j) = sc.N[j] / sc.S[j];
      if (G) g = (sc.gN[j] - f(begin + j) * sc.gS[j]) / sc.S[j];
    }
    if (G) G->col(begin + j) = g;
  }
}

// A run whose points spread over more than kScatteredSupports typical supports across (along the
// second-longest axis of their box, in frame units) is scattered: its box meets a large part of the
// tree, and a walk per point costs less. Rows of a grid and the vertices of a mesh stay runs.
constexpr double kScatteredSupports = 4.0;

template <int Dim>
bool PuModel<Dim>::scatteredRun(const Points<Dim>& X, Eigen::Index begin, Eigen::Index count) const {
  if (count < 2) return false;
  Vec<Dim> lo = X.col(begin), hi = lo;
  for (Eigen::Index j = 1; j < count; ++j) {
    lo = lo.cwiseMin(X.col(begin + j));
    hi = hi.cwiseMax(X.col(begin + j));
  }
  Vec<Dim> extent = (hi - lo) / frame_.q;  // along the world axes (callers' rows), in frame units
  std::sort(extent.data(), extent.data() + Dim);
  return extent[Dim - 2] > kScatteredSupports * typicalSupport_;
}

template <int Dim>
void PuModel<Dim>::evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) const {
  const Eigen::Index n = X.cols();
  f.resize(n);
  if (G) G->resize(Dim, n);
  if (options_.blend == PuBlend::Smooth) {
    using Scratch = PuRunScratch<Dim>;
    const Eigen::Index runs = (n + Scratch::kRun - 1) / Scratch::kRun;
#pragma omp parallel
    {
      Scratch sc;
#pragma omp for schedule(dynamic, 4)
      for (Eigen::Index r = 0; r < runs; ++r) {
        const Eigen::Index begin = r * Scratch::kRun, count = std::min(Scratch::kRun, n - begin);
        if (!scatteredRun(X, begin, count)) {
          evaluateRun(X, begin, count, f, G, sc);
          continue;
        }
        for (Eigen::Index j = 0; j < count; ++j) evaluateRun(X, begin + j, 1, f, G, sc);
      }
    }
    return;
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    if (G) {
      Vec<Dim> g;
      f(i) = evaluate(X.col(i), &g);
      G->col(i) = g;
    } else {
      f(i) = evaluate(X.col(i));
    }
  }
}

template <int Dim>
void PuModel<Dim>::evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const {
  const Eigen::Index n = X.cols();
  f.resize(n);
  valid.assign(static_cast<std::size_t>(n), 1);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    bool ok = true;
    f(i) = evaluateValid(X.col(i), nullptr, nullptr, &ok);
    valid[static_cast<std::size_t>(i)] = ok ? 1 : 0;
  }
}

template <int Dim>
Box<Dim> PuModel<Dim>::frameBox(const Box<Dim>& box) const {
  if (identityFrame_) return box;
  Box<Dim> yb{Vec<Dim>::Constant(std::numeric_limits<double>::infinity()),
              Vec<Dim>::Constant(-std::numeric_limits<double>::infinity())};
  for (int corner = 0; corner < (1 << Dim); ++corner) {
    Vec<Dim> c;
    for (int k = 0; k < Dim; ++k) c(k) = (corner >> k) & 1 ? box.hi(k) : box.lo(k);
    const Vec<Dim> y = frame_.applyInverse(c);
    yb.lo = yb.lo.cwiseMin(y);
    yb.hi = yb.hi.cwiseMax(y);
  }
  return yb;
}

template <int Dim>
std::unique_ptr<ImplicitField<Dim>> PuModel<Dim>::forGridCells(double cellDiagonal) const {
  if (options_.blend == PuBlend::Hard || !(cellDiagonal > 0)) return nullptr;
  return std::make_unique<PuNearField<Dim>>(*this, cellDiagonal);
}

template <int Dim>
int PuModel<Dim>::nearestSupport(const Vec<Dim>& x, double margin) const {
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  const double m = margin / frame_.q;
  const Box<Dim> query{y - Vec<Dim>::Constant(m), y + Vec<Dim>::Constant(m)};
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  forSupportsTouching(query, [&](int i) {
    const double d = leaves_[i].support.distanceTo(y);
    if (d <= m && (d < bestDistance || (d == bestDistance && i < best))) best = i, bestDistance = d;
  });
  return best;
}

template <int Dim>
bool PuModel<Dim>::supportNear(const Box<Dim>& box, double margin) const {
  Box<Dim> yb = frameBox(box);
  yb.lo.array() -= margin / frame_.q;
  yb.hi.array() += margin / frame_.q;
  bool found = false;
  forSupportsTouching(yb, [&](int) { found = true; });
  return found;
}

template <int Dim>
std::vector<std::pair<int, double>> PuModel<Dim>::weights(const Vec<Dim>& x) const {
  std::vector<std::pair<int, double>> out;
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  if (options_.blend == PuBlend::Hard) {
    out.emplace_back(tree_.locateLeaf(y), 1.0);
    return out;
  }
  const bool frozen[Dim] = {};
  double S = 0;
  forSupportsAt(y, [&](int i) {
    const double w = bump<Dim>(leaves_[i].support, y, frozen, nullptr, nullptr);
    if (w > 0) {
      out.emplace_back(i, w);
      S += w;
    }
  });
  for (auto& p : out) p.second /= S;
  return out;
}

template <int Dim>
double PuModel<Dim>::lipschitzBound(const Box<Dim>& box) const {
  if (options_.blend == PuBlend::Hard || !(minFactor_ > 1.0)) return std::numeric_limits<double>::infinity();
  const Box<Dim> yb = frameBox(box);
  const Vec<Dim> xc = box.center();
  const double reach = 0.5 * box.extent().norm();
  double sumGF = 0, sumG = 0, fMax = 0, lMax = 0, sMin = 0, factorMin = std::numeric_limits<double>::infinity();
  int touching = 0;
  forSupportsTouching(yb, [&](int i) {
    ++touching;
    const Leaf& leaf = leaves_[i];
    factorMin = std::min(factorMin, leaf.factor);
    double inv2 = 0, wMin = 1;
    for (int k = 0; k < Dim; ++k) {
      const double c = 0.5 * (leaf.support.lo(k) + leaf.support.hi(k));
      const double h = 0.5 * (leaf.support.hi(k) - leaf.support.lo(k));
      inv2 += 1.0 / (h * h);
      const double t = std::max(std::abs(yb.lo(k) - c), std::abs(yb.hi(k) - c)) / h;
      const double u = 1.0 - t * t;
      wMin *= u > 0 ? u * u * u : 0.0;
    }
    const double G = kMaxBumpSlope * std::sqrt(inv2) / frame_.q;  // ≥ ‖∇ₓwᵢ‖
    const double L = leaf.model.lipschitzBound(box);
    const double F = std::abs(leaf.model.value(xc)) + L * reach;  // ≥ |fᵢ| on the box
    sumGF += G * F;
    sumG += G;
    fMax = std::max(fMax, F);
    lMax = std::max(lMax, L);
    sMin += wMin;
  });
  if (touching == 0) return 0.0;  // no data reaches the box: f is the constant noDataValue()
  // Every point of a blended leaf box lies in its support, σ ≥ factorMin times larger (the leaf's
  // support touches yb): there |tₖ| ≤ 1/σ on every axis, so S ≥ (1 − 1/factorMin²)^(3·Dim) where
  // such boxes cover yb. The smallest factor of the supports here, not of the whole model: one
  // capped support elsewhere must not loosen every bound.
  if (factorMin > 1.0 && coveredByData(yb)) sMin = std::max(sMin, std::pow(1.0 - 1.0 / (factorMin * factorMin), 3 * Dim));
  // Where S has no positive lower bound f may jump to noDataValue(): no finite bound.
  if (!(sMin > 0)) return std::numeric_limits<double>::infinity();
  // Rounding of the sums: a relative 1e-12 margin.
  return (1.0 + 1e-12) * ((sumGF + fMax * sumG) / sMin + lMax);
}

template <int Dim>
PuModel<Dim> transformPu(const PuModel<Dim>& model, const Similarity<Dim>& T) {
  std::vector<typename PuModel<Dim>::Leaf> leaves = model.leaves();
  const int count = static_cast<int>(leaves.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < count; ++i)
    if (leaves[i].blended) leaves[i].model = transformModel<Dim>(leaves[i].model, T);
  return PuModel<Dim>(model.tree(), std::move(leaves), model.options(), composeSimilarity<Dim>(T, model.frame()),
                      model.dataReach());
}

template class PuModel<2>;
template class PuModel<3>;
template PuModel<2> transformPu<2>(const PuModel<2>&, const Similarity<2>&);
template PuModel<3> transformPu<3>(const PuModel<3>&, const Similarity<3>&);
template Similarity<2> composeSimilarity<2>(const Similarity<2>&, const Similarity<2>&);
template Similarity<3> composeSimilarity<3>(const Similarity<3>&, const Similarity<3>&);

}  // namespace hermite
