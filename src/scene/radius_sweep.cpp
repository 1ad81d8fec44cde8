#include "scene/radius_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <tuple>

#include "core/base/errors.h"
#include "core/mesh/zero_set_check.h"
#include "core/rbf/leave_one_out.h"
#include "scene/holdout_validation.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"

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

namespace {

// The region whose zero set the suggestion counts: view.bounds (or the default box), what is
// meshed and traced and where `fit` checks for a degenerate field.
template <int Dim>
Box<Dim> zeroSetBox(const Scene& s, const SceneFit<Dim>& fit) {
  return viewBounds<Dim>(s.view, fit.data.points);
}

// Leave-one-out (global HRBF) or k-fold (the rest) into the row's validation columns.
template <int Dim>
void validate(const Scene& s, const SceneFit<Dim>& fit, RadiusSweepRow& row) {
  try {
    if (s.fit.method == FitMethod::Hrbf && !fit.pu()) {
      row.validation = "leave-one-out";
      HrbfOptions o;
      o.kernel = Kernel{s.fit.kernel, s.fit.radius};
      o.polynomial = s.fit.polynomial;
      o.smoothing = s.fit.smoothing;
      const LeaveOneOutResult loo = hrbfLeaveOneOut<Dim>(fit.samples, o);
      row.looRmsValue = loo.rmsValue;
      row.looRmsGradient = loo.rmsGradient;
      row.looCombined = loo.combined;
      row.validationError = loo.combined;
    } else if (fit.samples.size() >= kHoldoutFolds) {
      row.validation = std::to_string(kHoldoutFolds) + "-fold";
      row.validationError = kFoldValidation<Dim>(s, fit.samples).combined;
    }
  } catch (const NumericalError& e) {
    row.looError = e.what();  // the fit stands; its validation error is undefined
  }
}

}  // namespace

std::string RadiusSweepRow::rejection() const {
  if (!ok()) return "failed";
  if (!(conditionEstimate <= kSuggestionMaxCondition)) return "ill-conditioned";
  if (!std::isfinite(validationError)) return "validation not finite";
  return "";
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
  validate<Dim>(s, fit, row);
  try {
    const ZeroSetCheck z = checkZeroSet<Dim>(fit.unmaskedField(), zeroSetBox<Dim>(s, fit), fit.data);
    row.components = z.components;
    row.spuriousComponents = z.spurious;
    row.signFailures = z.signFailures;
    row.flatFraction = z.degenerate.flatFraction;
    row.degenerate = z.degenerate.degenerate;
  } catch (const std::exception& e) {
    row.zeroSetError = e.what();
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
  for (int i = 0; i < int(rows.size()); ++i) {
    const RadiusSweepRow& r = rows[std::size_t(i)];
    if (!r.rejection().empty()) continue;
    if (best < 0) {
      best = i;
      continue;
    }
    const RadiusSweepRow& b = rows[std::size_t(best)];
    const auto key = [](const RadiusSweepRow& x) { return std::make_tuple(x.defects(), x.degenerate ? 1 : 0); };
    if (key(r) < key(b) || (key(r) == key(b) && r.validationError < b.validationError)) best = i;
  }
  return best;
}

std::string radiusSweepVerdict(const RadiusSweepRow& r, int dim) {
  if (!r.ok()) return "failed: " + r.error;
  const std::string why = r.rejection();
  if (!why.empty()) return "ill-conditioned";
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s %-9.3g", r.validation == "leave-one-out" ? "loo" : r.validation.c_str(),
                r.validationError);
  std::string out = buf;
  if (r.components < 0) return out + "  zero set not checked: " + r.zeroSetError;
  const char* noun = dim == 2 ? (r.components == 1 ? "curve" : "curves") : (r.components == 1 ? "surface" : "surfaces");
  std::snprintf(buf, sizeof buf, "  %d %s", r.components, noun);
  out += buf;
  if (r.defects() > 0) {
    std::snprintf(buf, sizeof buf, " (%d spurious, %d sign failure%s)", r.spuriousComponents, r.signFailures,
                  r.signFailures == 1 ? "" : "s");
    out += buf;
  }
  if (r.degenerate) {
    std::snprintf(buf, sizeof buf, ", degenerate (flat over %.0f%%)", 100 * r.flatFraction);
    out += buf;
  }
  return out;
}

std::string radiusSweepCsv(const std::vector<RadiusSweepRow>& rows, const std::vector<std::string>* images) {
  std::string out =
      "radius,radius_in_spacing,solver,condition_estimate,max_abs_f,max_grad_error,loo_rms_value,loo_rms_gradient,"
      "loo_combined,fit_ms,suggested,error";
  out += ",validation,validation_error,components,spurious_components,sign_failures,flat_fraction,degenerate,rejected";
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
    std::snprintf(buf, sizeof buf, ",%s,%.6g,%d,%d,%d,%.4f,%d,%s", r.validation.c_str(), r.validationError,
                  r.components, r.spuriousComponents, r.signFailures, r.flatFraction, r.degenerate ? 1 : 0,
                  r.rejection().c_str());
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
