#include "scene/patch_document.h"

#include <cmath>

#include "core/base/errors.h"

namespace hermite {

std::string_view patchFormName(PatchForm f) { return nameIn<PatchForm>(kPatchFormNames, f); }

bool PatchSpec::operator==(const PatchSpec& o) const {
  if (!(preset == o.preset && splits == o.splits && domain == o.domain && form == o.form && showError == o.showError &&
        showIsoLines == o.showIsoLines && showHandles == o.showHandles && tessellation == o.tessellation &&
        knots.size() == o.knots.size()))
    return false;
  for (std::size_t k = 0; k < knots.size(); ++k)
    if (knots[k].X != o.knots[k].X || knots[k].Xu != o.knots[k].Xu || knots[k].Xv != o.knots[k].Xv ||
        knots[k].Xuv != o.knots[k].Xuv)
      return false;
  return true;
}

const std::vector<std::pair<std::string, std::string>>& patchPresets() {
  static const std::vector<std::pair<std::string, std::string>> presets{
      {"torus", "the torus X(u,v) = ((2 + cos v) cos u, (2 + cos v) sin u, sin v): exact data, error shown"},
      {"flat", "the plane z = 0 over [-1, 1]^2"},
      {"saddle", "the saddle z = xy over [-1, 1]^2 (non-zero twist)"},
      {"zero-twist", "the torus data with every twist set to zero (compare with 'torus')"},
  };
  return presets;
}

namespace {

void checkSpec(const PatchSpec& s) {
  for (int k = 0; k < 2; ++k)
    if (s.splits[k] < 1 || s.splits[k] > 16) throw InputError("patch.splits: each must be in 1..16");
  if (!(s.domain[0] < s.domain[1]) || !(s.domain[2] < s.domain[3]))
    throw InputError("patch.domain: must be [U0, U1, V0, V1] with U0 < U1 and V0 < V1");
}

std::vector<double> uniform(double a, double b, int n) {
  std::vector<double> k(n + 1);
  for (int i = 0; i <= n; ++i) k[i] = a + (b - a) * i / n;
  k[n] = b;
  return k;
}

// The preset's surface at domain parameters (u, v).
KnotData presetData(const std::string& preset, const PatchSpec& s, double u, double v) {
  if (preset == "torus") return torusKnotData(u, v);
  if (preset == "zero-twist") {
    KnotData d = torusKnotData(u, v);
    d.Xuv.setZero();
    return d;
  }
  // flat and saddle: x, y in [-1, 1] over the domain.
  const double su = 2.0 / (s.domain[1] - s.domain[0]), sv = 2.0 / (s.domain[3] - s.domain[2]);
  const double x = -1 + su * (u - s.domain[0]), y = -1 + sv * (v - s.domain[2]);
  KnotData d;
  if (preset == "flat") {
    d.X = Vec<3>(x, y, 0);
    d.Xu = Vec<3>(su, 0, 0);
    d.Xv = Vec<3>(0, sv, 0);
    d.Xuv.setZero();
    return d;
  }
  if (preset == "saddle") {
    d.X = Vec<3>(x, y, x * y);
    d.Xu = Vec<3>(su, 0, su * y);
    d.Xv = Vec<3>(0, sv, sv * x);
    d.Xuv = Vec<3>(0, 0, su * sv);
    return d;
  }
  std::string names;
  for (const auto& [n, _] : patchPresets()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("patch.preset: unknown preset '" + preset + "' (expected one of: " + names + ")");
}

double meanSpacing(const std::vector<double>& k) { return (k.back() - k.front()) / double(k.size() - 1); }

struct CornerSigns {
  int a, b;            // corner of the patch (0 or 1 in s and t)
  double ss, st;       // σs, σt: +1 at the 0 side, −1 at the 1 side
};
CornerSigns cornerOf(int p, int q) {
  const int a = p < 2 ? 0 : 1, b = q < 2 ? 0 : 1;
  return {a, b, a == 0 ? 1.0 : -1.0, b == 0 ? 1.0 : -1.0};
}

}  // namespace

std::vector<double> patchKnotsU(const PatchSpec& s) {
  checkSpec(s);
  return uniform(s.domain[0], s.domain[1], s.splits[0]);
}
std::vector<double> patchKnotsV(const PatchSpec& s) {
  checkSpec(s);
  return uniform(s.domain[2], s.domain[3], s.splits[1]);
}

std::vector<KnotData> patchKnotData(const PatchSpec& s) {
  const std::vector<double> u = patchKnotsU(s), v = patchKnotsV(s);
  if (!s.knots.empty()) {
    if (s.knots.size() != u.size() * v.size())
      throw InputError("patch.knots: " + std::to_string(s.knots.size()) + " entries for " + std::to_string(u.size()) +
                       " × " + std::to_string(v.size()) + " knots (splits + 1 in each direction)");
    return s.knots;
  }
  return PatchGrid::sampleKnots(u, v, [&](double a, double b) { return presetData(s.preset, s, a, b); });
}

PatchGrid buildPatchGrid(const PatchSpec& s) { return PatchGrid(patchKnotsU(s), patchKnotsV(s), patchKnotData(s)); }

std::array<std::array<Vec<3>, 4>, 4> patchControlPoints(const PatchSpec& s, const std::vector<KnotData>& knots, int i,
                                                        int j) {
  const std::vector<double> u = patchKnotsU(s), v = patchKnotsV(s);
  const double du = u[i + 1] - u[i], dv = v[j + 1] - v[j];
  std::array<std::array<Vec<3>, 4>, 4> c;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const KnotData& k = knots[(i + a) * v.size() + (j + b)];
      const double ss = a == 0 ? 1 : -1, st = b == 0 ? 1 : -1;
      const Vec<3> Xs = du * k.Xu, Xt = dv * k.Xv, Xst = du * dv * k.Xuv;
      const int p = a * 3, q = b * 3, pn = p + int(ss), qn = q + int(st);
      c[p][q] = k.X;
      c[pn][q] = k.X + ss * Xs / 3;
      c[p][qn] = k.X + st * Xt / 3;
      c[pn][qn] = k.X + ss * Xs / 3 + st * Xt / 3 + ss * st * Xst / 9;
    }
  return c;
}

Vec<3> patchHandlePosition(const PatchSpec& s, const std::vector<KnotData>& knots, const PatchHandle& h) {
  if (h.kind == PatchHandle::Control) return patchControlPoints(s, knots, h.a, h.b)[h.p][h.q];
  const std::vector<double> u = patchKnotsU(s), v = patchKnotsV(s);
  const double lu = meanSpacing(u) / 3, lv = meanSpacing(v) / 3;
  const KnotData& k = knots[h.a * v.size() + h.b];
  switch (h.kind) {
    case PatchHandle::Point: return k.X;
    case PatchHandle::TangentU: return k.X + lu * k.Xu;
    case PatchHandle::TangentV: return k.X + lv * k.Xv;
    case PatchHandle::Twist: return k.X + lu * k.Xu + lv * k.Xv + lu * lv * k.Xuv;
    case PatchHandle::Control: break;
  }
  return k.X;
}

std::vector<std::pair<PatchHandle, Vec<3>>> patchHandles(const PatchSpec& s) {
  const std::vector<KnotData> knots = patchKnotData(s);
  std::vector<std::pair<PatchHandle, Vec<3>>> out;
  if (s.form == PatchForm::Hermite) {
    for (int a = 0; a <= s.splits[0]; ++a)
      for (int b = 0; b <= s.splits[1]; ++b)
        for (auto kind : {PatchHandle::Point, PatchHandle::TangentU, PatchHandle::TangentV, PatchHandle::Twist}) {
          PatchHandle h{kind, a, b, 0, 0};
          out.emplace_back(h, patchHandlePosition(s, knots, h));
        }
  } else {
    for (int i = 0; i < s.splits[0]; ++i)
      for (int j = 0; j < s.splits[1]; ++j) {
        const auto c = patchControlPoints(s, knots, i, j);
        for (int p = 0; p < 4; ++p)
          for (int q = 0; q < 4; ++q) out.emplace_back(PatchHandle{PatchHandle::Control, i, j, p, q}, c[p][q]);
      }
  }
  return out;
}

PatchSpec movePatchHandle(const PatchSpec& spec, const PatchHandle& h, const Vec<3>& position) {
  PatchSpec s = spec;
  s.knots = patchKnotData(spec);
  const std::vector<double> u = patchKnotsU(s), v = patchKnotsV(s);
  if (h.kind != PatchHandle::Control) {
    KnotData& k = s.knots[h.a * v.size() + h.b];
    const double lu = meanSpacing(u) / 3, lv = meanSpacing(v) / 3;
    switch (h.kind) {
      case PatchHandle::Point: k.X = position; break;
      case PatchHandle::TangentU: k.Xu = (position - k.X) / lu; break;
      case PatchHandle::TangentV: k.Xv = (position - k.X) / lv; break;
      case PatchHandle::Twist: k.Xuv = (position - k.X - lu * k.Xu - lv * k.Xv) / (lu * lv); break;
      case PatchHandle::Control: break;
    }
    return s;
  }
  // Bézier: the corner's four control points, one of them moved, give the corner's data.
  auto c = patchControlPoints(s, s.knots, h.a, h.b);
  c[h.p][h.q] = position;
  const CornerSigns cs = cornerOf(h.p, h.q);
  const int p = cs.a * 3, q = cs.b * 3, pn = p + int(cs.ss), qn = q + int(cs.st);
  const double du = u[h.a + 1] - u[h.a], dv = v[h.b + 1] - v[h.b];
  KnotData& k = s.knots[(h.a + cs.a) * v.size() + (h.b + cs.b)];
  k.X = c[p][q];
  k.Xu = 3 * cs.ss * (c[pn][q] - c[p][q]) / du;
  k.Xv = 3 * cs.st * (c[p][qn] - c[p][q]) / dv;
  k.Xuv = 9 * cs.ss * cs.st * (c[pn][qn] - c[pn][q] - c[p][qn] + c[p][q]) / (du * dv);
  return s;
}

}  // namespace hermite
