#include "core/shapes/presets.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>

#include <Eigen/Geometry>

#include "core/base/errors.h"
#include "core/shapes/bunny_data.h"

namespace hermite {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// 1/φ: the golden-ratio step that spreads i·kGolden (mod 1) evenly for every prefix.
constexpr double kGolden = 0.6180339887498948482;
constexpr int kMaxGenerated = 10'000'000;

constexpr double kTorusMajor = 0.7;
constexpr double kTorusMinor = 0.3;
constexpr double kTwoToriMajor = 5.0 / 9.0;
constexpr double kTwoToriMinor = 1.0 / 6.0;
constexpr double kCurveAmplitude = 0.35;

double fraction(double x) { return x - std::floor(x); }

// ---- bunny: the embedded mesh vertices, parsed once ------------------------------------------

const HermiteSamples<3>& bunnyFull() {
  static const HermiteSamples<3> samples = [] {
    const std::string_view text = embeddedBunnyXyzn();
    std::vector<double> values;
    values.reserve(6 * 2048);
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
      while (p < end && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')) ++p;
      if (p == end) break;
      double v = 0;
      const auto [next, ec] = std::from_chars(p, end, v);
      if (ec != std::errc()) throw InputError("embedded bunny.xyzn: unreadable number");
      values.push_back(v);
      p = next;
    }
    if (values.size() % 6 != 0 || values.empty()) {
      throw InputError("embedded bunny.xyzn: expected 6 numbers per line");
    }
    const Eigen::Index n = static_cast<Eigen::Index>(values.size() / 6);
    const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> table(values.data(), 6, n);
    HermiteSamples<3> s;
    s.points = table.topRows<3>();
    s.normals = table.bottomRows<3>();
    return s;
  }();
  return samples;
}

// The number of vertices in the embedded bunny: its non-blank lines, counted without parsing (the
// preset table needs the count in every process; bunnyFull() parses only when the bunny is used).
int bunnyVertexCount() {
  const std::string_view text = embeddedBunnyXyzn();
  int lines = 0;
  bool blank = true;
  for (const char c : text) {
    if (c == '\n') {
      lines += blank ? 0 : 1;
      blank = true;
    } else if (c != ' ' && c != '\r' && c != '\t') {
      blank = false;
    }
  }
  return lines + (blank ? 0 : 1);
}

// Farthest-point sampling from column 0, ties to the lowest index: the first k of a larger
// sample are the sample of size k. O(N·count).
std::vector<Eigen::Index> farthestPointOrder(const Points<3>& P, int count) {
  const Eigen::Index n = P.cols();
  std::vector<Eigen::Index> order;
  order.reserve(count);
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  Eigen::Index current = 0;
  for (int k = 0; k < count; ++k) {
    order.push_back(current);
    Eigen::Index best = 0;
    double bestDistance = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
      nearest(i) = std::min(nearest(i), (P.col(i) - P.col(current)).squaredNorm());
      if (nearest(i) > bestDistance) {
        bestDistance = nearest(i);
        best = i;
      }
    }
    current = best;
  }
  return order;
}

HermiteSamples<3> makeBunny(int count) {
  const HermiteSamples<3>& full = bunnyFull();
  if (count == full.size()) return full;
  HermiteSamples<3> s;
  s.points.resize(3, count);
  s.normals.resize(3, count);
  const std::vector<Eigen::Index> order = farthestPointOrder(full.points, count);
  for (int k = 0; k < count; ++k) {
    s.points.col(k) = full.points.col(order[k]);
    s.normals.col(k) = full.normals.col(order[k]);
  }
  return s;
}

// ---- spheres and circles ----------------------------------------------------------------------

HermiteSamples<3> makeSphere6() {
  HermiteSamples<3> s;
  s.points.resize(3, 6);
  for (int axis = 0; axis < 3; ++axis) {
    s.points.col(2 * axis) = Vec<3>::Unit(axis);
    s.points.col(2 * axis + 1) = -Vec<3>::Unit(axis);
  }
  s.normals = s.points;
  return s;
}

// Spherical Fibonacci points: z stratified uniformly (equal-area bands), longitude by the
// golden ratio.
HermiteSamples<3> makeFibonacciSphere(int count) {
  HermiteSamples<3> s;
  s.points.resize(3, count);
  s.normals.resize(3, count);
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = kTwoPi * fraction(i * kGolden);
    const Vec<3> p(rho * std::cos(phi), rho * std::sin(phi), z);
    s.normals.col(i) = p.normalized();
    s.points.col(i) = s.normals.col(i);
  }
  return s;
}

HermiteSamples<2> makeCircle(int count) {
  HermiteSamples<2> s;
  s.points.resize(2, count);
  s.normals.resize(2, count);
  for (int i = 0; i < count; ++i) {
    const double theta = kTwoPi * i / count;
    const Vec<2> p(std::cos(theta), std::sin(theta));
    s.normals.col(i) = p.normalized();
    s.points.col(i) = s.normals.col(i);
  }
  return s;
}

// ---- tori -------------------------------------------------------------------------------------

// Two unit vectors completing the unit axis a to a right-handed frame (e1, e2, a).
std::pair<Vec<3>, Vec<3>> frameAround(const Vec<3>& a) {
  const Vec<3> helper = std::abs(a.x()) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY();
  const Vec<3> e1 = (helper - helper.dot(a) * a).normalized();
  return {e1, a.cross(e1)};
}

// `count` samples written to columns [first, first + count) of s. The samples lie on rings of
// constant tube angle v, spaced like a hexagonal cover of the area 4π²Rr; each ring holds a
// share of the samples proportional to its length 2π(R + r cos v) (largest remainders), so the
// density is uniform in area; rings are rotated against each other by the golden ratio.
// (A Fibonacci lattice uniform in area keeps nearest neighbours at only 0.2–0.5 of the
// hexagonal spacing on this anisotropic surface; the rings keep 0.8–0.9.)
void sampleTorus(const TorusGeometry& t, int count, HermiteSamples<3>& s, int first) {
  const auto [e1, e2] = frameAround(t.axis);
  const double area = 4.0 * std::numbers::pi * std::numbers::pi * t.major * t.minor;
  const double spacing = std::sqrt(area / count / (0.5 * std::sqrt(3.0)));
  const int rings = std::max(1, static_cast<int>(std::lround(kTwoPi * t.minor / spacing)));
  std::vector<double> ideal(rings);
  double total = 0;
  for (int j = 0; j < rings; ++j) {
    ideal[j] = t.major + t.minor * std::cos(kTwoPi * j / rings);
    total += ideal[j];
  }
  std::vector<int> perRing(rings);
  int assigned = 0;
  for (int j = 0; j < rings; ++j) {
    ideal[j] *= count / total;
    perRing[j] = static_cast<int>(std::floor(ideal[j]));
    assigned += perRing[j];
  }
  std::vector<int> byRemainder(rings);
  for (int j = 0; j < rings; ++j) byRemainder[j] = j;
  std::stable_sort(byRemainder.begin(), byRemainder.end(),
                   [&](int a, int b) { return ideal[a] - perRing[a] > ideal[b] - perRing[b]; });
  for (int k = 0; k < count - assigned; ++k) ++perRing[byRemainder[k]];

  int column = first;
  for (int j = 0; j < rings; ++j) {
    const double v = kTwoPi * j / rings;
    const double offset = fraction(j * kGolden);
    for (int k = 0; k < perRing[j]; ++k) {
      const double u = kTwoPi * (k + offset) / perRing[j];
      const Vec<3> radial = std::cos(u) * e1 + std::sin(u) * e2;
      const Vec<3> n = (std::cos(v) * radial + std::sin(v) * t.axis).normalized();
      s.points.col(column) = t.centre + t.major * radial + t.minor * n;
      s.normals.col(column) = n;
      ++column;
    }
  }
}

HermiteSamples<3> makeTori(const std::vector<TorusGeometry>& tori, int count) {
  HermiteSamples<3> s;
  s.points.resize(3, count);
  s.normals.resize(3, count);
  const int m = static_cast<int>(tori.size());
  int first = 0;
  for (int k = 0; k < m; ++k) {
    const int share = count / m + (k < count % m ? 1 : 0);
    sampleTorus(tori[k], share, s, first);
    first += share;
  }
  return s;
}

// ---- curve2d ----------------------------------------------------------------------------------

struct CurvePoint {
  Vec<2> p;    // r(θ)(cos θ, sin θ)
  Vec<2> dp;   // d/dθ
  Vec<2> ddp;  // d²/dθ²
};

CurvePoint curvePoint(double theta) {
  const double r = curve2dRadius(theta);
  const double dr = -3.0 * kCurveAmplitude * std::sin(3.0 * theta);
  const double ddr = -9.0 * kCurveAmplitude * std::cos(3.0 * theta);
  const Vec<2> e(std::cos(theta), std::sin(theta));
  const Vec<2> ePerp(-e.y(), e.x());
  return {r * e, dr * e + r * ePerp, (ddr - r) * e + 2.0 * dr * ePerp};
}

double curveSpeed(double theta) { return curvePoint(theta).dp.norm(); }

// 5-point Gauss–Legendre on [a, b]: the curve is analytic and the table cells are short, so
// this is exact to rounding.
double integrateSpeed(double a, double b) {
  static constexpr std::array<double, 5> nodes{0.0, 0.5384693101056831, -0.5384693101056831,
                                               0.9061798459386640, -0.9061798459386640};
  static constexpr std::array<double, 5> weights{0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                                 0.2369268850561891, 0.2369268850561891};
  const double mid = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  double sum = 0;
  for (int k = 0; k < 5; ++k) sum += weights[k] * curveSpeed(mid + half * nodes[k]);
  return half * sum;
}

// Maximum of a smooth function of θ: coarse table, then golden-section search around the best
// entry (the value is then exact to rounding: the function is flat at its maximum).
double maximise(const std::function<double(double)>& f) {
  constexpr int kTable = 4096;
  constexpr double h = kTwoPi / kTable;
  int best = 0;
  for (int j = 1; j < kTable; ++j) {
    if (f(j * h) > f(best * h)) best = j;
  }
  double a = (best - 1) * h;
  double b = (best + 1) * h;
  double c = b - kGolden * (b - a);
  double d = a + kGolden * (b - a);
  double fc = f(c);
  double fd = f(d);
  for (int iteration = 0; iteration < 200 && b - a > 1e-14; ++iteration) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kGolden * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kGolden * (b - a);
      fd = f(d);
    }
  }
  return std::max({fc, fd, f(best * h)});
}

HermiteSamples<2> makeCurve2d(int count) {
  const Curve2dFrame& frame = curve2dFrame();
  // Cumulative arc length at θ_j = 2πj/M.
  constexpr int kTable = 4096;
  constexpr double h = kTwoPi / kTable;
  std::vector<double> cumulative(kTable + 1, 0.0);
  for (int j = 0; j < kTable; ++j) cumulative[j + 1] = cumulative[j] + integrateSpeed(j * h, (j + 1) * h);
  const double length = cumulative[kTable];

  HermiteSamples<2> s;
  s.points.resize(2, count);
  s.normals.resize(2, count);
  for (int k = 0; k < count; ++k) {
    const double target = length * k / count;
    const int j = std::clamp(
        static_cast<int>(std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin()) - 1, 0,
        kTable - 1);
    const double theta0 = j * h;
    double theta = theta0 + h * (target - cumulative[j]) / (cumulative[j + 1] - cumulative[j]);
    for (int iteration = 0; iteration < 20; ++iteration) {
      const double step = (cumulative[j] + integrateSpeed(theta0, theta) - target) / curveSpeed(theta);
      theta -= step;
      if (std::abs(step) < 1e-15) break;
    }
    const CurvePoint c = curvePoint(theta);
    // Counter-clockwise: the outward normal is the tangent turned clockwise.
    s.normals.col(k) = Vec<2>(c.dp.y(), -c.dp.x()).normalized();
    s.points.col(k) = frame.scale * (c.p - frame.centre);
  }
  return s;
}

// ---- the table of presets and the checks ------------------------------------------------------

std::string presetList(int dimension) {
  std::string list;
  for (const PresetInfo& info : allPresets()) {
    if (info.dimension != dimension) continue;
    if (!list.empty()) list += ", ";
    list += info.name;
  }
  return list;
}

const PresetInfo& checkedPreset(std::string_view name, int dimension, int& count) {
  const PresetInfo* found = nullptr;
  for (const PresetInfo& info : allPresets()) {
    if (info.name == name) found = &info;
  }
  std::ostringstream message;
  if (!found) {
    message << "unknown preset '" << name << "'; " << dimension << "D presets: " << presetList(dimension);
    throw InputError(message.str());
  }
  if (found->dimension != dimension) {
    message << "preset '" << name << "' is " << found->dimension << "D, expected a " << dimension
            << "D preset: " << presetList(dimension);
    throw InputError(message.str());
  }
  if (count == 0) count = found->defaultCount;
  if (count < found->minCount || count > found->maxCount) {
    message << "preset '" << name << "': count " << count << " out of range; valid: 0 (the preset's own, "
            << found->defaultCount << ")";
    if (found->minCount == found->maxCount) {
      message << " or " << found->minCount;
    } else {
      message << " or [" << found->minCount << ", " << found->maxCount << "]";
    }
    throw InputError(message.str());
  }
  return *found;
}

}  // namespace

double curve2dRadius(double theta) { return 1.0 + kCurveAmplitude * std::cos(3.0 * theta); }

const Curve2dFrame& curve2dFrame() {
  static const Curve2dFrame frame = [] {
    Curve2dFrame f;
    const double xMax = maximise([](double t) { return curvePoint(t).p.x(); });
    const double xMin = -maximise([](double t) { return -curvePoint(t).p.x(); });
    const double yMax = maximise([](double t) { return curvePoint(t).p.y(); });
    const double yMin = -maximise([](double t) { return -curvePoint(t).p.y(); });
    f.centre = Vec<2>(0.5 * (xMin + xMax), 0.5 * (yMin + yMax));
    const double farthest = maximise([&](double t) { return (curvePoint(t).p - f.centre).norm(); });
    f.scale = 1.0 / farthest;
    return f;
  }();
  return frame;
}

std::vector<TorusGeometry> presetTori(std::string_view name) {
  if (name == "torus") return {{Vec<3>::Zero(), Vec<3>::UnitZ(), kTorusMajor, kTorusMinor}};
  if (name == "two-tori") {
    const Vec<3> offset(0.5 * kTwoToriMajor, 0, 0);
    return {{-offset, Vec<3>::UnitZ(), kTwoToriMajor, kTwoToriMinor},
            {offset, Vec<3>::UnitY(), kTwoToriMajor, kTwoToriMinor}};
  }
  throw InputError("presetTori: '" + std::string(name) + "' is not a torus preset (torus, two-tori)");
}

const std::vector<PresetInfo>& allPresets() {
  static const std::vector<PresetInfo> presets = [] {
    const int bunnyCount = bunnyVertexCount();
    return std::vector<PresetInfo>{
        {"sphere6", 3, 6, {6}, "the unit sphere sampled at ±x, ±y, ±z", 6, 6},
        {"sphere", 3, 100, {100}, "unit sphere, Fibonacci (golden spiral) points", 4, kMaxGenerated},
        {"torus", 3, 200, {200}, "torus about z, R = 0.7, r = 0.3, area-uniform staggered rings", 4,
         kMaxGenerated},
        {"two-tori", 3, 400, {120, 400}, "two interlinked tori (xy- and xz-planes), samples split evenly", 8,
         kMaxGenerated},
        {"bunny", 3, bunnyCount, {64, 600}, "Stanford bunny (npm 'bunny'), area-weighted vertex normals; "
                                            "sub-samples by farthest-point sampling", 4, bunnyCount},
        {"curve2d", 2, 80, {40, 80, 200, 400}, "star r = 1 + 0.35 cos 3θ, uniform in arc length", 3,
         kMaxGenerated},
        {"circle", 2, 16, {16}, "unit circle, uniform angles", 3, kMaxGenerated},
    };
  }();
  return presets;
}

const PresetInfo& presetInfo(std::string_view name) {
  for (const PresetInfo& info : allPresets()) {
    if (info.name == name) return info;
  }
  throw InputError("unknown preset '" + std::string(name) + "'; 3D presets: " + presetList(3) +
                   "; 2D presets: " + presetList(2));
}

HermiteSamples<2> makePreset2d(std::string_view name, int count) {
  const PresetInfo& info = checkedPreset(name, 2, count);
  if (info.name == "curve2d") return makeCurve2d(count);
  return makeCircle(count);
}

HermiteSamples<3> makePreset3d(std::string_view name, int count) {
  const PresetInfo& info = checkedPreset(name, 3, count);
  if (info.name == "sphere6") return makeSphere6();
  if (info.name == "sphere") return makeFibonacciSphere(count);
  if (info.name == "bunny") return makeBunny(count);
  return makeTori(presetTori(info.name), count);
}

}  // namespace hermite
