#include "core/mesh/degenerate_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace hermite {

template <int Dim>
FlatnessScale flatnessScale(const ImplicitField<Dim>& field, const HermiteSamples<Dim>& samples, double tolerance) {
  FlatnessScale s;
  s.tolerance = tolerance;
  s.spacing = meanSampleSpacing<Dim>(samples.points);
  Eigen::VectorXd f;
  Points<Dim> G;
  field.evaluateBatch(samples.points, f, &G);
  std::vector<double> norms(std::size_t(G.cols()));
  for (Eigen::Index i = 0; i < G.cols(); ++i) norms[std::size_t(i)] = G.col(i).norm();
  if (!norms.empty()) {
    std::nth_element(norms.begin(), norms.begin() + norms.size() / 2, norms.end());
    s.gradient = norms[norms.size() / 2];
  }
  // One sample (h = 0) or a field flat at its own samples: judge by unit scales instead.
  if (!(s.spacing > 0)) s.spacing = 1;
  if (!(s.gradient > 0) || !std::isfinite(s.gradient)) s.gradient = 1;
  return s;
}

std::string DegenerateFieldReport::message() const {
  if (!degenerate) return "";
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "degenerate field: f and its gradient are nearly zero over %.0f%% of the view bounds (|f| < %.0e of the "
                "data's scale), so the zero set there is noise; add a polynomial or increase r",
                100 * flatFraction, scale.tolerance);
  return buf;
}

template <int Dim>
DegenerateFieldReport detectDegenerateField(const ImplicitField<Dim>& field, const Box<Dim>& box,
                                            const HermiteSamples<Dim>& samples, const DegenerateFieldOptions& options) {
  DegenerateFieldReport r;
  r.scale = flatnessScale(field, samples, options.tolerance);
  const int res = options.resolution > 0 ? options.resolution : (Dim == 2 ? 200 : 40);
  const Vec<Dim> extent = box.extent();
  const double cell = extent.maxCoeff() / res;
  std::array<int, 3> n{1, 1, 1};
  Eigen::Index total = 1;
  for (int k = 0; k < Dim; ++k) {
    n[std::size_t(k)] = std::max(2, int(std::lround(extent(k) / cell)) + 1);
    total *= n[std::size_t(k)];
  }
  // Grid points, the first axis fastest.
  Points<Dim> X(Dim, total);
  for (Eigen::Index i = 0; i < total; ++i) {
    Eigen::Index rest = i;
    for (int k = 0; k < Dim; ++k) {
      const Eigen::Index ik = rest % n[std::size_t(k)];
      rest /= n[std::size_t(k)];
      X(k, i) = box.lo(k) + extent(k) * double(ik) / double(n[std::size_t(k)] - 1);
    }
  }
  Eigen::VectorXd f;
  Points<Dim> G;
  field.evaluateBatch(X, f, &G);
  std::vector<char> valid;
  if (!field.everywhereValid()) field.validBatch(X, valid);
  Eigen::Index flat = 0, counted = 0;
  for (Eigen::Index i = 0; i < total; ++i) {
    if (!valid.empty() && !valid[std::size_t(i)]) continue;
    ++counted;
    if (r.scale.flat(f(i), G.col(i).norm())) ++flat;
  }
  r.flatFraction = counted > 0 ? double(flat) / double(counted) : 0;
  r.degenerate = r.flatFraction > options.largeFraction;
  return r;
}

template FlatnessScale flatnessScale<2>(const ImplicitField<2>&, const HermiteSamples<2>&, double);
template FlatnessScale flatnessScale<3>(const ImplicitField<3>&, const HermiteSamples<3>&, double);
template DegenerateFieldReport detectDegenerateField<2>(const ImplicitField<2>&, const Box<2>&,
                                                        const HermiteSamples<2>&, const DegenerateFieldOptions&);
template DegenerateFieldReport detectDegenerateField<3>(const ImplicitField<3>&, const Box<3>&,
                                                        const HermiteSamples<3>&, const DegenerateFieldOptions&);

}  // namespace hermite
