#include "core/mesh/centre_vertices.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/mesh/marching_grid.h"

namespace hermite {

namespace {

constexpr int kLineSamples = 8;      // samples of f on each side of the mean, to find a sign change
constexpr int kRootSteps = 60;       // Illinois false-position steps on the sign change
constexpr double kRootWidth = 1e-9;  // of the segment: a bracket this narrow is the root

// One centre's search: the line x + t·d, t ∈ [t0, t1] inside its box, and the sign change on it.
struct CentreLine {
  Vec<3> x, d;  // the polygon's mean, unit direction
  double t0 = 0, t1 = 0;
  double a = 0, b = 0, fa = 0, fb = 0;  // bracket: f(a) and f(b) differ in sign (f ≥ 0 is outside)
  signed char lastMoved = 0;            // Illinois: which end moved last (−1 a, +1 b)
  bool found = false;
  double guess = 0;                     // the bracket's linear root: how far the root is from x
  Vec<3> at(double t) const { return x + t * d; }
};

// [t0, t1] ∋ 0: the part of the line through x (inside [lo, hi]) that stays in the box.
void clipToBox(CentreLine& line, const Vec<3>& lo, const Vec<3>& hi) {
  double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (line.d[k] == 0) continue;
    double a = (lo[k] - line.x[k]) / line.d[k], b = (hi[k] - line.x[k]) / line.d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  line.t0 = std::isfinite(t0) ? std::min(t0, 0.0) : 0.0;
  line.t1 = std::isfinite(t1) ? std::max(t1, 0.0) : 0.0;
}

// The sign change nearest t = 0 among f0 = f(x) and the samples fs[k] at t1·(k+1)/K (k < K) and
// t0·(k+1−K)/K (k ≥ K); on a tie of steps, the side whose linear root is nearer.
void nearestSignChange(CentreLine& line, double f0, const double* fs) {
  double prevPos = f0, prevNeg = f0;
  for (int k = 1; k <= kLineSamples && !line.found; ++k) {
    const double fp = fs[k - 1], fn = fs[kLineSamples + k - 1];
    const double tp = line.t1 * k / kLineSamples, tn = line.t0 * k / kLineSamples;
    const double tpPrev = line.t1 * (k - 1) / kLineSamples, tnPrev = line.t0 * (k - 1) / kLineSamples;
    const bool pos = (prevPos < 0) != (fp < 0) && tp > tpPrev, neg = (prevNeg < 0) != (fn < 0) && tn < tnPrev;
    const double rootPos = tpPrev + (tp - tpPrev) * prevPos / (prevPos - fp);
    const double rootNeg = tnPrev + (tn - tnPrev) * prevNeg / (prevNeg - fn);
    if (pos && (!neg || std::abs(rootPos) <= std::abs(rootNeg))) {
      line.a = tpPrev, line.fa = prevPos, line.b = tp, line.fb = fp, line.found = true, line.guess = rootPos;
    } else if (neg) {
      line.a = tnPrev, line.fa = prevNeg, line.b = tn, line.fb = fn, line.found = true, line.guess = rootNeg;
    }
    prevPos = fp;
    prevNeg = fn;
  }
}

// Brackets for the lines: f at 2K points of each, one batch.
void findBrackets(const ImplicitField<3>& field, std::vector<CentreLine>& lines, const Eigen::VectorXd& f0,
                  const CancelToken* cancel) {
  const Eigen::Index n = static_cast<Eigen::Index>(lines.size());
  Points<3> S(3, 2 * kLineSamples * n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 1; k <= kLineSamples; ++k) {
      S.col(2 * kLineSamples * i + k - 1) = lines[i].at(lines[i].t1 * k / kLineSamples);
      S.col(2 * kLineSamples * i + kLineSamples + k - 1) = lines[i].at(lines[i].t0 * k / kLineSamples);
    }
  Eigen::VectorXd fs;
  Points<3> gs;
  detail::evaluateChunked<3>(field, S, fs, gs, cancel);
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::isfinite(f0[i])) nearestSignChange(lines[i], f0[i], fs.data() + 2 * kLineSamples * i);
}

double falsePosition(const CentreLine& line) {
  const double t = line.a + (line.b - line.a) * line.fa / (line.fa - line.fb);
  return std::isfinite(t) ? std::clamp(t, std::min(line.a, line.b), std::max(line.a, line.b)) : line.a;
}

// The roots of the bracketed lines, by batched Illinois steps; returns each line's parameter.
std::vector<double> solveBrackets(const ImplicitField<3>& field, std::vector<CentreLine>& lines,
                                  const CancelToken* cancel) {
  std::vector<double> t(lines.size(), 0.0);
  std::vector<std::size_t> active;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].found) active.push_back(i);
  for (int step = 0; step < kRootSteps && !active.empty(); ++step) {
    Points<3> X(3, static_cast<Eigen::Index>(active.size()));
    for (std::size_t k = 0; k < active.size(); ++k) {
      t[active[k]] = falsePosition(lines[active[k]]);
      X.col(static_cast<Eigen::Index>(k)) = lines[active[k]].at(t[active[k]]);
    }
    Eigen::VectorXd f;
    Points<3> G;
    detail::evaluateChunked<3>(field, X, f, G, cancel);
    std::vector<std::size_t> next;
    for (std::size_t k = 0; k < active.size(); ++k) {
      CentreLine& line = lines[active[k]];
      const double fk = f[static_cast<Eigen::Index>(k)];
      if (fk == 0 || !std::isfinite(fk)) continue;
      detail::illinoisUpdate(line.a, line.fa, line.b, line.fb, line.lastMoved, t[active[k]], fk);
      if (std::abs(line.b - line.a) > kRootWidth * (line.t1 - line.t0)) next.push_back(active[k]);
      else t[active[k]] = std::abs(line.fa) <= std::abs(line.fb) ? line.a : line.b;
    }
    active.swap(next);
  }
  return t;
}

// The lines each centre searches (kDirections per centre): its area normal, ∇f at its start, and
// the three axes, each clipped to its box. The first keeps the fan a fan; the others find the
// surface where a part thinner than the cell runs along the area normal (no root on it there).
constexpr int kDirections = 5;

std::vector<CentreLine> candidateLines(const Points<3>& X, const Points<3>& axis, const Points<3>& G,
                                       const Points<3>& lo, const Points<3>& hi) {
  std::vector<CentreLine> lines(static_cast<std::size_t>(kDirections * X.cols()));
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    const Vec<3> dirs[kDirections] = {axis.col(i), G.col(i), Vec<3>::UnitX(), Vec<3>::UnitY(), Vec<3>::UnitZ()};
    for (int k = 0; k < kDirections; ++k) {
      CentreLine& line = lines[static_cast<std::size_t>(kDirections * i + k)];
      line.x = X.col(i);
      const double len = dirs[k].norm();
      if (len > 0 && std::isfinite(len)) line.d = dirs[k] / len;
      else line.d.setZero();
      clipToBox(line, lo.col(i), hi.col(i));
    }
  }
  return lines;
}

// Per centre, its line whose sign change lies nearest the start (none found: the first line).
std::vector<CentreLine> nearestLines(const std::vector<CentreLine>& lines) {
  std::vector<CentreLine> best(lines.size() / kDirections);
  for (std::size_t i = 0; i < best.size(); ++i) {
    best[i] = lines[kDirections * i];
    for (int k = 1; k < kDirections; ++k) {
      const CentreLine& c = lines[kDirections * i + static_cast<std::size_t>(k)];
      if (c.found && (!best[i].found || std::abs(c.guess) < std::abs(best[i].guess))) best[i] = c;
    }
  }
  return best;
}

}  // namespace

CentreVertexReport placeCentreVertices(const ImplicitField<3>& field, Points<3>& X, const Points<3>& axis,
                                       const Points<3>& lo, const Points<3>& hi, Points<3>& G,
                                       const CancelToken* cancel) {
  CentreVertexReport report;
  const Eigen::Index n = X.cols();
  report.centres = static_cast<int>(n);
  Eigen::VectorXd f;
  detail::evaluateChunked<3>(field, X, f, G, cancel);
  std::vector<CentreLine> candidates = candidateLines(X, axis, G, lo, hi);
  Eigen::VectorXd fStart(kDirections * n);  // f at each candidate line's start
  for (Eigen::Index i = 0; i < fStart.size(); ++i) fStart[i] = f[i / kDirections];
  findBrackets(field, candidates, fStart, cancel);
  std::vector<CentreLine> lines = nearestLines(candidates);
  const std::vector<double> t = solveBrackets(field, lines, cancel);
  for (std::size_t i = 0; i < lines.size(); ++i) X.col(static_cast<Eigen::Index>(i)) = lines[i].at(t[i]);
  detail::evaluateChunked<3>(field, X, f, G, cancel);
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool onZeroSet = lines[static_cast<std::size_t>(i)].found || f[i] == 0;
    if (onZeroSet) report.maxAbsF = std::max(report.maxAbsF, std::abs(f[i]));
    else ++report.offZeroSet;
  }
  return report;
}

}  // namespace hermite
