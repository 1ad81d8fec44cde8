// `hermite-lab patch-table [--samples N] [--splits 1x1,2x1,...] [--domain U0,U1,V0,V1] [--json]`:
// the torus error study of core/patch/torus_patch_study.h as a table or JSON (docs/cli.md).

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "core/base/errors.h"
#include "core/patch/torus_patch_study.h"

namespace hermite::app {

namespace {

std::vector<std::array<int, 2>> parseSplits(const std::string& text) {
  std::vector<std::array<int, 2>> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    int n = 0, m = 0;
    char x = 0, extra = 0;
    if (std::sscanf(item.c_str(), "%d%c%d%c", &n, &x, &m, &extra) != 3 || (x != 'x' && x != 'X') || n < 1 || m < 1)
      throw UsageError("patch-table: --splits: '" + item + "' is not NxM with N, M ≥ 1 (e.g. 2x1)");
    out.push_back({n, m});
  }
  if (out.empty()) throw UsageError("patch-table: --splits is empty");
  return out;
}

std::array<double, 4> parseDomain(const std::string& text) {
  std::array<double, 4> d{};
  char extra = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &d[0], &d[1], &d[2], &d[3], &extra) != 4)
    throw UsageError("patch-table: --domain: '" + text + "' is not U0,U1,V0,V1");
  for (const double v : d)
    if (!std::isfinite(v)) throw UsageError("patch-table: --domain: '" + text + "' has a value that is not finite");
  return d;
}

}  // namespace

int runPatchTable(const PatchTableArgs& args) {
  PatchStudyOptions o;
  o.samples = args.samples;
  if (!args.splits.empty()) o.splits = parseSplits(args.splits);
  if (!args.domain.empty()) o.domain = parseDomain(args.domain);
  const std::vector<PatchStudyRow> rows = torusPatchStudy(o);
  for (const PatchStudyRow& r : rows)
    if (!std::isfinite(r.error[0]) || !std::isfinite(r.error[1]) || !std::isfinite(r.error[2]) ||
        !std::isfinite(r.hermiteBezierMaxDiff))
      throw NumericalError("patch-table: the errors of the " + std::to_string(r.splits[0]) + "x" +
                           std::to_string(r.splits[1]) + " patches are not finite (is --domain finite and moderate?)");
  if (args.json) {
    nlohmann::json out;
    out["rows"] = nlohmann::json::array();
    for (const PatchStudyRow& r : rows)
      out["rows"].push_back({{"splits", {r.splits[0], r.splits[1]}},
                             {"error", {r.error[0], r.error[1], r.error[2]}},
                             {"hermite_bezier_max_diff", r.hermiteBezierMaxDiff}});
    out["samples"] = o.samples;
    out["domain"] = {o.domain[0], o.domain[1], o.domain[2], o.domain[3]};
    writeStdout(out.dump(2) + "\n");
    return 0;
  }
  char line[256];
  std::snprintf(line, sizeof line, "torus patches on [%g, %g] x [%g, %g], %d x %d samples per patch\n",
                o.domain[0], o.domain[1], o.domain[2], o.domain[3], o.samples, o.samples);
  writeStdout(line);
  writeStdout("splits     error x        error y        error z        |Hermite - Bezier|\n");
  for (const PatchStudyRow& r : rows) {
    std::snprintf(line, sizeof line, "%-8s   %-13.6e  %-13.6e  %-13.6e  %.3e\n",
                  (std::to_string(r.splits[0]) + "x" + std::to_string(r.splits[1])).c_str(), r.error[0],
                  r.error[1], r.error[2], r.hermiteBezierMaxDiff);
    writeStdout(line);
  }
  return 0;
}

}  // namespace hermite::app
