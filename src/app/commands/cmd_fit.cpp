// `hermite-lab fit SCENE [--json] [--coefficients] [--verify]` and the default fit report.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <type_traits>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "app/commands/terminal_progress.h"
#include "app/gui/fit_worker.h"
#include "app/gui/scene_loading.h"
#include "core/base/errors.h"
#include "core/points/hermite_samples.h"
#include "scene/data_reach_mask.h"
#include "scene/degenerate_check.h"
#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

using json = nlohmann::json;

// A global model (or a PU leaf's): its kernel, centres, coefficients and polynomial; an
// RBF-offset model adds its shift.
template <int Dim, class Model>
json modelJson(const Scene& scene, const Model& m) {
  json out;
  out["method"] = std::string(fitMethodName(scene.fit.method));
  out["kernel"] = std::string(kernelName(m.kernel().type));
  out["radius"] = m.kernel().radius;
  out["polynomial"] = std::string(polynomialName(m.polynomial()));
  out["dimension"] = Dim;
  json centres = json::array(), alpha = json::array(), beta = json::array();
  for (Eigen::Index j = 0; j < m.centres().cols(); ++j) {
    json c = json::array();
    for (int k = 0; k < Dim; ++k) c.push_back(m.centres()(k, j));
    centres.push_back(std::move(c));
    alpha.push_back(m.alpha()(j));
    if (m.hasBeta()) {
      json b = json::array();
      for (int k = 0; k < Dim; ++k) b.push_back(m.beta()(k, j));
      beta.push_back(std::move(b));
    }
  }
  out["centres"] = std::move(centres);
  out["alpha"] = std::move(alpha);
  out["beta"] = std::move(beta);
  json poly = json::array();
  for (Eigen::Index k = 0; k < m.poly().size(); ++k) poly.push_back(m.poly()(k));
  out["poly"] = std::move(poly);
  json polyOrigin = json::array();  // the polynomial is p(x − poly_origin); zero for data near the origin
  for (int k = 0; k < Dim; ++k) polyOrigin.push_back(m.polyOrigin()(k));
  out["poly_origin"] = std::move(polyOrigin);
  if constexpr (std::is_same_v<Model, RbfOffsetModel<Dim>>) out["shift"] = m.shift();
  return out;
}

template <int Dim>
json boxJson(const Box<Dim>& b) {
  json lo = json::array(), hi = json::array();
  for (int k = 0; k < Dim; ++k) {
    lo.push_back(b.lo(k));
    hi.push_back(b.hi(k));
  }
  return {{"lo", std::move(lo)}, {"hi", std::move(hi)}};
}

// A PU model: its frame (world x = scale·R·y + translate for box coordinates y), options and
// boxes, each with its box, support and local model in the shape of the global `model`.
template <int Dim>
json puModelJson(const Scene& scene, const PuModel<Dim>& pu) {
  json out;
  out["method"] = "partition-of-unity";
  out["kernel"] = std::string(kernelName(scene.fit.kernel));
  out["polynomial"] = std::string(polynomialName(scene.fit.polynomial));
  out["dimension"] = Dim;
  out["blend"] = std::string(puBlendName(pu.options().blend));
  out["overlap"] = pu.options().overlap;
  json R = json::array();
  for (int r = 0; r < Dim; ++r) {
    json row = json::array();
    for (int c = 0; c < Dim; ++c) row.push_back(pu.frame().R(r, c));
    R.push_back(std::move(row));
  }
  json t = json::array();
  for (int k = 0; k < Dim; ++k) t.push_back(pu.frame().t(k));
  out["frame"] = {{"rotation", std::move(R)}, {"translate", std::move(t)}, {"scale", pu.frame().q}};
  out["root"] = boxJson<Dim>(pu.tree().root());
  json boxes = json::array();
  for (int i = 0; i < static_cast<int>(pu.leaves().size()); ++i) {
    const auto& leaf = pu.leaves()[i];
    json b = boxJson<Dim>(pu.tree().leafBox(i));
    b["support"] = boxJson<Dim>(leaf.support);
    b["samples"] = leaf.samples;
    b["blended"] = leaf.blended;
    if (leaf.blended) b["model"] = modelJson<Dim>(scene, leaf.model);
    boxes.push_back(std::move(b));
  }
  out["boxes"] = std::move(boxes);
  return out;
}

// The coefficients of either model kind (docs/cli.md, fit --coefficients).
template <int Dim>
json fittedModelJson(const Scene& scene, const FittedModel<Dim>& model) {
  return std::visit(
      [&](const auto& m) -> json {
        if constexpr (std::is_same_v<std::decay_t<decltype(*m)>, PuModel<Dim>>)
          return puModelJson<Dim>(scene, *m);
        else
          return modelJson<Dim>(scene, *m);
      },
      model);
}

template <int Dim>
json fitReportJson(const Scene& scene, const SceneFit<Dim>& fit, bool coefficients) {
  const FitResiduals r = fitResiduals(fit);
  json out;
  out["n_samples"] = fit.report.nSamples;
  out["n_unknowns"] = fit.report.nUnknowns;
  out["solver"] = fit.report.solver;
  out["condition_estimate"] = fit.report.conditionEstimate;
  out["max_abs_f"] = r.maxAbsF;
  out["max_grad_error"] = r.maxGradError;
  out["fit_ms"] = fit.report.fitMs;
  out["assembly_ms"] = fit.report.assemblyMs;
  out["solve_ms"] = fit.report.solveMs;
  out["factor_ms"] = fit.report.factorMs;
  out["factor_gflops"] = fit.report.factorGflops;
  json phases = json::object();  // a phase that ran twice (a fallback) counts once, summed
  for (const auto& [phase, ms] : fit.report.solvePhasesMs) phases[phase] = phases.value(phase, 0.0) + ms;
  out["solve_phases_ms"] = phases;
  out["warnings"] = fit.warnings;
  if (fit.degenerateField)
    out["degenerate_field"] = {{"degenerate", fit.degenerateField->degenerate},
                               {"flat_fraction", fit.degenerateField->flatFraction},
                               {"tolerance", fit.degenerateField->scale.tolerance}};
  else if (!degenerateCheckApplies(scene.fit.kernel))
    out["degenerate_field"] = {{"degenerate", false},
                               {"skipped", "the kernel grows with distance: its field is not flat away from the data"}};
  if (const PuModel<Dim>* pu = fit.pu()) {
    out["partition"] = {{"boxes", fit.puReport.boxes},
                        {"max_box_samples", fit.puReport.maxBoxSamples},
                        {"max_support_samples", fit.puReport.maxSupportSamples},
                        {"grown_supports", fit.puReport.grownSupports},
                        {"fitted_boxes", fit.puReport.fittedBoxes},
                        {"unknowns", fit.puReport.unknowns},
                        {"blend", std::string(puBlendName(pu->options().blend))}};
  } else {
    out["partition"] = nullptr;
  }
  if (fit.transformed) {
    const TransformReport& t = fit.transform;
    const auto orNull = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
    out["transform"] = {{"update_ms", t.updateMs},           {"resolve_ms", orNull(t.resolveMs)},
                        {"max_abs_df", orNull(t.maxAbsDf)}, {"max_grad_diff", orNull(t.maxGradDiff)},
                        {"method", t.method},               {"exact", t.exact},
                        {"probes", t.probes}};
  } else {
    out["transform"] = nullptr;
  }
  // Added keys (never renamed): what was fitted.
  out["dimension"] = Dim;
  out["method"] = std::string(fitMethodName(scene.fit.method));
  out["kernel"] = std::string(kernelName(scene.fit.kernel));
  out["radius"] = scene.fit.radius;
  out["polynomial"] = std::string(polynomialName(scene.fit.polynomial));
  out["smoothing"] = scene.fit.smoothing;
  out["mean_spacing"] = meanSampleSpacing<Dim>(fit.samples.points);
  out["partition_chosen"] = fit.pu() ? "pu" : "dense";  // what fit.partition.enabled ("auto": by size) ran
  // Whether the global field ends at the samples' data reach for mesh, render and the GUI
  // (fit.reach_mask; the partition of unity always does).
  out["data_reach_mask"] = dataReachApplies<Dim>(scene, fit);
  if (coefficients) out["model"] = fittedModelJson<Dim>(scene, fit.model);
  return out;
}

std::string sci(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void printReadable(const Scene& scene, const json& j) {
  std::string s;
  const Kernel k{scene.fit.kernel, scene.fit.radius};
  s += "scene        " + scene.sourceName + " (" + std::string(sceneModeName(scene.mode)) + ", " +
       std::to_string(j["n_samples"].get<int>()) + " samples, mean spacing " + sci(j["mean_spacing"]) + ")\n";
  s += "fit          " + std::string(fitMethodName(scene.fit.method)) + ", kernel " +
       std::string(kernelName(scene.fit.kernel)) +
       (k.usesRadius() ? " r = " + sci(scene.fit.radius) + " (" +
                             sci(scene.fit.radius / std::max(j["mean_spacing"].get<double>(), 1e-300)) +
                             " × spacing)"
                       : " (no radius)") +
       ", polynomial " + std::string(polynomialName(scene.fit.polynomial)) +
       ", smoothing " + sci(scene.fit.smoothing) + "\n";
  s += "unknowns     " + std::to_string(j["n_unknowns"].get<int>()) + "\n";
  s += "solver       " + j["solver"].get<std::string>() + ", condition estimate " +
       sci(j["condition_estimate"]) + "\n";
  s += "residuals    max |f(p)| = " + sci(j["max_abs_f"]) + ", max |grad f(p) - n| = " +
       sci(j["max_grad_error"]) + "\n";
  s += "fit time     " + sci(j["fit_ms"]) + " ms (assembly " + sci(j["assembly_ms"]) + " ms, solve " +
       sci(j["solve_ms"]) + " ms)\n";
  if (!j["partition"].is_null())
    s += "partition    " + std::to_string(j["partition"]["boxes"].get<int>()) + " boxes, at most " +
         std::to_string(j["partition"]["max_box_samples"].get<int>()) + " samples per box, " +
         std::to_string(j["partition"]["max_support_samples"].get<int>()) + " per local fit (" +
         j["partition"]["blend"].get<std::string>() + " blend)\n";
  if (j["data_reach_mask"].get<bool>())
    s += "data reach   the surface ends within " + sci(scene.fit.partition.dataReach) +
         " local spacings of the samples in mesh, render and the GUI (fit.reach_mask)\n";
  if (const json& t = j["transform"]; !t.is_null()) {
    s += "transform    " + t["method"].get<std::string>() + "; update " + sci(t["update_ms"]) + " ms";
    if (!t["resolve_ms"].is_null())
      s += ", re-solve " + sci(t["resolve_ms"]) + " ms, max |df| " + sci(t["max_abs_df"]) + ", max |d grad f| " +
           sci(t["max_grad_diff"]);
    s += "\n";
  }
  if (j["warnings"].empty()) {
    s += "warnings     none\n";
  } else {
    for (const auto& w : j["warnings"]) s += "warning      " + w.get<std::string>() + "\n";
  }
  writeStdout(s);
}

// The report, or NumericalError (exit 3) when the fitted field is not finite at the samples:
// a report of NaN residuals would pass for a result.
template <int Dim>
json fitAndReport(const Scene& scene, bool coefficients) {
  SceneFit<Dim> fit = fitScene<Dim>(scene);
  checkDegenerateField<Dim>(scene, fit);
  json report = fitReportJson<Dim>(scene, fit, coefficients);
  const double maxAbsF = report["max_abs_f"].get<double>(), maxGradError = report["max_grad_error"].get<double>();
  if (!std::isfinite(maxAbsF) || !std::isfinite(maxGradError))
    throw NumericalError("fit: the fitted field is not finite at the samples (max |f(p)| = " + sci(maxAbsF) +
                         ", max |grad f(p) - n| = " + sci(maxGradError) + ")");
  return report;
}

}  // namespace

int runFit(const FitArgs& args) {
  Scene scene = loadCommandScene(args.scene);
  if (args.verify) scene.transform.verify = true;
  json j;
  {
    const TerminalProgress progress("fitting " + scene.sourceName);
    j = scene.dimension() == 2 ? fitAndReport<2>(scene, args.coefficients) : fitAndReport<3>(scene, args.coefficients);
  }
  if (args.json) {
    writeStdout(j.dump(2) + "\n");
  } else {
    printReadable(scene, j);
    if (args.coefficients) writeStdout(j["model"].dump(2) + "\n");
  }
  return 0;
}

std::string fittedModelJson(const FitOutcome& fit) {
  std::string model;
  if (fit.visitImplicit([&](const auto& f) { model = fitReportJson(fit.scene, f, true)["model"].dump(2); }))
    return model;
  throw InputError("no fitted model to export: " + fit.error);
}

}  // namespace hermite::app
