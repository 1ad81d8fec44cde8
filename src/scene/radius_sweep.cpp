#include "scene/radius_sweep.h"

#include <cmath>
#include <cstdio>
#include <regex>

#include "core/base/errors.h"
#include "core/rbf/leave_one_out.h"
#include "scene/scene_fit.h"

namespace hermite {

std::vector<double> logSpacedRadii(double a, double b, int k) {
  if (!(a > 0) || !(b >= a) || !std::isfinite(b))
    throw InputError("radius sweep: bounds must satisfy 0 < A ≤ B (got " + std::to_string(a) + ", " +
                     std::to_string(b) + ")");
  if (k < 1 || k > 1000) throw InputError("radius sweep: the count must be in [1, 1000] (got " + std::to_string(k) + ")");
  std::vector<double> r(k);
  for (int i = 0; i < k; ++i) r[i] = k == 1 ? a : a * std::pow(b / a, double(i) / (k - 1));
  if (k > 1) r.back() = b;  // exactly the bound the user typed
  return r;
}

std::vector<double> parseRadiiArgument(const std::string& text) {
  static const std::regex pattern(R"(^\s*([^:]+):([^:]+):\s*([0-9]+)\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, pattern))
    throw UsageError("--radii must be A:B:K, e.g. 0.05:2:8 (got '" + text + "')");
  try {
    std::size_t used = 0;
    const double a = std::stod(m[1].str(), &used);
    if (used != m[1].str().size()) throw std::invalid_argument("A");
    const double b = std::stod(m[2].str(), &used);
    if (used != m[2].str().size()) throw std::invalid_argument("B");
    return logSpacedRadii(a, b, std::stoi(m[3].str()));
  } catch (const InputError& e) {
    throw UsageError(std::string("--radii: ") + e.what());
  } catch (const std::exception&) {
    throw UsageError("--radii must be A:B:K with numbers A, B and a count K (got '" + text + "')");
  }
}

template <int Dim>
RadiusSweepRow radiusSweepRow(const Scene& s, const SceneFit<Dim>& fit, double spacing) {
  RadiusSweepRow row;
  row.radius = s.fit.radius;
  row.radiusInSpacing = spacing > 0 ? s.fit.radius / spacing : 0;
  const FitResiduals res = fitResiduals(fit);
  row.solver = fit.report.solver;
  row.conditionEstimate = fit.report.conditionEstimate;
  row.maxAbsF = res.maxAbsF;
  row.maxGradError = res.maxGradError;
  row.fitMs = fit.report.fitMs;
  if (s.fit.method == FitMethod::Hrbf && !fit.pu()) {
    HrbfOptions o;
    o.kernel = Kernel{s.fit.kernel, s.fit.radius};
    o.polynomial = s.fit.polynomial;
    o.smoothing = s.fit.smoothing;
    try {
      const LeaveOneOutResult loo = hrbfLeaveOneOut<Dim>(fit.samples, o);
      row.looRmsValue = loo.rmsValue;
      row.looRmsGradient = loo.rmsGradient;
      row.looCombined = loo.combined;
    } catch (const NumericalError& e) {
      row.looError = e.what();  // the fit stands; its leave-one-out error is undefined
    }
  }
  return row;
}

template <int Dim>
std::vector<RadiusSweepRow> sweepRadii(const Scene& scene, const std::vector<double>& radii,
                                       const std::atomic<bool>* cancel, std::atomic<float>* progress) {
  std::vector<std::string> warnings;
  const HermiteSamples<Dim> samples = sceneSamples<Dim>(scene, warnings);
  const double spacing = meanSampleSpacing<Dim>(samples.points);
  std::vector<RadiusSweepRow> rows;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    if (cancel && cancel->load()) break;
    RadiusSweepRow row;
    row.radius = radii[k];
    row.radiusInSpacing = spacing > 0 ? radii[k] / spacing : 0;
    Scene s = scene;
    s.fit.radius = radii[k];
    try {
      row = radiusSweepRow<Dim>(s, fitScene<Dim>(s), spacing);
    } catch (const std::exception& e) {
      row.error = e.what();
    }
    rows.push_back(std::move(row));
    if (progress) progress->store(float(k + 1) / float(radii.size()));
  }
  return rows;
}

int suggestedRadiusIndex(const std::vector<RadiusSweepRow>& rows) {
  int best = -1;
  for (int i = 0; i < int(rows.size()); ++i)
    if (rows[i].ok() && std::isfinite(rows[i].looCombined) && (best < 0 || rows[i].looCombined < rows[best].looCombined))
      best = i;
  return best;
}

std::string radiusSweepCsv(const std::vector<RadiusSweepRow>& rows, const std::vector<std::string>* images) {
  std::string out =
      "radius,radius_in_spacing,solver,condition_estimate,max_abs_f,max_grad_error,loo_rms_value,loo_rms_gradient,"
      "loo_combined,fit_ms,suggested,error";
  out += images ? ",image\n" : "\n";
  const int best = suggestedRadiusIndex(rows);
  char buf[512];
  for (int i = 0; i < int(rows.size()); ++i) {
    const RadiusSweepRow& r = rows[i];
    std::string err = r.error;
    for (char& c : err)
      if (c == '"' || c == '\n' || c == ',') c = c == ',' ? ';' : ' ';
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.3f,%d,\"%s\"", r.radius,
                  r.radiusInSpacing, r.solver.c_str(), r.conditionEstimate, r.maxAbsF, r.maxGradError, r.looRmsValue,
                  r.looRmsGradient, r.looCombined, r.fitMs, i == best ? 1 : 0, err.c_str());
    out += buf;
    if (images) out += "," + (*images)[std::size_t(i)];
    out += "\n";
  }
  return out;
}

template RadiusSweepRow radiusSweepRow<2>(const Scene&, const SceneFit<2>&, double);
template RadiusSweepRow radiusSweepRow<3>(const Scene&, const SceneFit<3>&, double);
template std::vector<RadiusSweepRow> sweepRadii<2>(const Scene&, const std::vector<double>&, const std::atomic<bool>*,
                                                   std::atomic<float>*);
template std::vector<RadiusSweepRow> sweepRadii<3>(const Scene&, const std::vector<double>&, const std::atomic<bool>*,
                                                   std::atomic<float>*);

}  // namespace hermite
