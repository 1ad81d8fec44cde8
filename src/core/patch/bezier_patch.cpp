#include "core/patch/bezier_patch.h"

namespace hermite {

const Eigen::Matrix4d& hermiteToBezierMatrix() {
  static const Eigen::Matrix4d M = [] {
    Eigen::Matrix4d m;
    m << 1, 0, 0, 0,          //
        1, 1.0 / 3, 0, 0,     //
        0, 0, -1.0 / 3, 1,    //
        0, 0, 0, 1;
    return m;
  }();
  return M;
}

const Eigen::Matrix4d& bezierToHermiteMatrix() {
  static const Eigen::Matrix4d M = [] {
    Eigen::Matrix4d m;
    m << 1, 0, 0, 0,   //
        -3, 3, 0, 0,   //
        0, 0, -3, 3,   //
        0, 0, 0, 1;
    return m;
  }();
  return M;
}

BezierPatch toBezier(const HermitePatch& h) {
  const Eigen::Matrix4d& M = hermiteToBezierMatrix();
  BezierPatch b;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix4d B = M * h.C[k] * M.transpose();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) b.P[i][j](k) = B(i, j);
  }
  return b;
}

HermitePatch toHermite(const BezierPatch& b) {
  const Eigen::Matrix4d& Mi = bezierToHermiteMatrix();
  HermitePatch h;
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix4d B;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) B(i, j) = b.P[i][j](k);
    h.C[k] = Mi * B * Mi.transpose();
  }
  return h;
}

namespace {

// de Casteljau on a cubic control polygon: point and derivative d/dt at t.
std::pair<Vec<3>, Vec<3>> casteljau(const std::array<Vec<3>, 4>& b, double t) {
  const double u = 1 - t;
  const Vec<3> a0 = u * b[0] + t * b[1], a1 = u * b[1] + t * b[2], a2 = u * b[2] + t * b[3];
  const Vec<3> q0 = u * a0 + t * a1, q1 = u * a1 + t * a2;
  return {u * q0 + t * q1, 3.0 * (q1 - q0)};
}

// Splits a cubic control polygon at t into [0, t] and [t, 1].
std::pair<std::array<Vec<3>, 4>, std::array<Vec<3>, 4>> splitCurve(const std::array<Vec<3>, 4>& b, double t) {
  const double u = 1 - t;
  const Vec<3> a0 = u * b[0] + t * b[1], a1 = u * b[1] + t * b[2], a2 = u * b[2] + t * b[3];
  const Vec<3> q0 = u * a0 + t * a1, q1 = u * a1 + t * a2;
  const Vec<3> r = u * q0 + t * q1;
  return {{b[0], a0, q0, r}, {r, q1, a2, b[3]}};
}

}  // namespace

SurfacePoint BezierPatch::evaluate(double s, double t) const {
  std::array<Vec<3>, 4> rowPoint, rowTangent;  // along s: the rows evaluated in t
  for (int i = 0; i < 4; ++i) std::tie(rowPoint[i], rowTangent[i]) = casteljau(P[i], t);
  SurfacePoint out;
  std::tie(out.X, out.Xs) = casteljau(rowPoint, s);
  std::tie(out.Xt, out.Xst) = casteljau(rowTangent, s);
  return out;
}

std::pair<BezierPatch, BezierPatch> BezierPatch::splitT(double t) const {
  BezierPatch a, b;
  for (int i = 0; i < 4; ++i) std::tie(a.P[i], b.P[i]) = splitCurve(P[i], t);
  return {a, b};
}

std::pair<BezierPatch, BezierPatch> BezierPatch::splitS(double s) const {
  BezierPatch a, b;
  for (int j = 0; j < 4; ++j) {
    const std::array<Vec<3>, 4> column{P[0][j], P[1][j], P[2][j], P[3][j]};
    const auto [lo, hi] = splitCurve(column, s);
    for (int i = 0; i < 4; ++i) {
      a.P[i][j] = lo[i];
      b.P[i][j] = hi[i];
    }
  }
  return {a, b};
}

}  // namespace hermite
