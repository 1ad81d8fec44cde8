#include "core/trace/ray_root.h"

namespace hermite {

namespace {

int signOf(double v) { return (v > 0) - (v < 0); }

}  // namespace

ProbeVerdict judgeProbe(double previous, double f, ZeroRule rule) {
  if (rule == ZeroRule::StopAtZero) {
    if (f == 0) return ProbeVerdict::Root;
    return signOf(previous) * signOf(f) < 0 ? ProbeVerdict::SignChange : ProbeVerdict::NoChange;
  }
  return (f == 0 || (previous < 0) != (f < 0)) ? ProbeVerdict::SignChange : ProbeVerdict::NoChange;
}

bool RootBracket::narrow(double f) {
  bool onLoSide;
  if (rule_ == ZeroRule::StopAtZero) {
    if (f == 0) return true;
    onLoSide = negativeLo_ ? f < 0 : f > 0;  // NaN: past the root
  } else {
    onLoSide = f != 0 && (f < 0) == negativeLo_;  // NaN: positive
  }
  const double m = probe();
  if (onLoSide)
    lo_ = m;
  else
    hi_ = m;
  return false;
}

std::optional<double> refineRayRoot(const ImplicitField<3>& field, const Ray& ray, double lo, double hi,
                                    const RayRootOptions& options) {
  double ta = lo, fa = field.evaluate(ray.at(lo));
  if (fa == 0) return lo;
  for (int s = 1; s <= options.samples; ++s) {
    const double tb = lo + (hi - lo) * s / options.samples;
    const double fb = field.evaluate(ray.at(tb));
    const ProbeVerdict verdict = judgeProbe(fa, fb, options.rule);
    if (verdict == ProbeVerdict::Root) return tb;
    if (verdict == ProbeVerdict::SignChange) {
      RootBracket bracket(ta, fa, tb, options.rule);
      while (!bracket.settled(options.tolerance))
        if (bracket.narrow(field.evaluate(ray.at(bracket.probe())))) break;
      return bracket.probe();
    }
    ta = tb;
    fa = fb;
  }
  return std::nullopt;
}

}  // namespace hermite
