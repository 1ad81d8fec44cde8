#include "core/patch/hermite_patch.h"

namespace hermite {

Eigen::Vector4d hermiteBasis(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {1 - 3 * t2 + 2 * t3, t - 2 * t2 + t3, t3 - t2, 3 * t2 - 2 * t3};
}

Eigen::Vector4d hermiteBasisDerivative(double t) {
  const double t2 = t * t;
  return {-6 * t + 6 * t2, 1 - 4 * t + 3 * t2, 3 * t2 - 2 * t, 6 * t - 6 * t2};
}

namespace {
// Row of C holding data at s = a: value rows are 0 (a = 0) and 3 (a = 1); s-derivative rows
// are 1 (a = 0) and 2 (a = 1). Columns likewise for t.
int valueIndex(int a) { return a == 0 ? 0 : 3; }
int derivativeIndex(int a) { return a == 0 ? 1 : 2; }

Vec<3> entry(const std::array<PatchMatrix, 3>& C, int row, int col) {
  return {C[0](row, col), C[1](row, col), C[2](row, col)};
}
void setEntry(std::array<PatchMatrix, 3>& C, int row, int col, const Vec<3>& v) {
  for (int k = 0; k < 3; ++k) C[k](row, col) = v(k);
}
}  // namespace

Vec<3> HermitePatch::point(int a, int b) const { return entry(C, valueIndex(a), valueIndex(b)); }
Vec<3> HermitePatch::sTangent(int a, int b) const { return entry(C, derivativeIndex(a), valueIndex(b)); }
Vec<3> HermitePatch::tTangent(int a, int b) const { return entry(C, valueIndex(a), derivativeIndex(b)); }
Vec<3> HermitePatch::twist(int a, int b) const { return entry(C, derivativeIndex(a), derivativeIndex(b)); }
void HermitePatch::setPoint(int a, int b, const Vec<3>& v) { setEntry(C, valueIndex(a), valueIndex(b), v); }
void HermitePatch::setSTangent(int a, int b, const Vec<3>& v) { setEntry(C, derivativeIndex(a), valueIndex(b), v); }
void HermitePatch::setTTangent(int a, int b, const Vec<3>& v) { setEntry(C, valueIndex(a), derivativeIndex(b), v); }
void HermitePatch::setTwist(int a, int b, const Vec<3>& v) { setEntry(C, derivativeIndex(a), derivativeIndex(b), v); }

SurfacePoint HermitePatch::evaluate(double s, double t) const {
  const Eigen::Vector4d hs = hermiteBasis(s), ht = hermiteBasis(t);
  const Eigen::Vector4d ds = hermiteBasisDerivative(s), dt = hermiteBasisDerivative(t);
  SurfacePoint p;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector4d Cht = C[k] * ht, Cdt = C[k] * dt;
    p.X(k) = hs.dot(Cht);
    p.Xs(k) = ds.dot(Cht);
    p.Xt(k) = hs.dot(Cdt);
    p.Xst(k) = ds.dot(Cdt);
  }
  return p;
}

}  // namespace hermite
