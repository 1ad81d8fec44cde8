// `hermite-lab mesh SCENE -o OUT.{glb,gltf,ply,obj} [--resolution N] [--set ...]` (docs/cli.md):
// the fitted field's zero set over `view.bounds` by marching cubes (3D) or marching squares (2D:
// closed polylines as OBJ `l` elements or SVG paths). One summary line on stdout.

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>

#include "app/commands/commands.h"
#include "app/commands/kept_until_exit.h"
#include "app/commands/output.h"
#include "app/commands/output_path.h"
#include "app/commands/terminal_progress.h"
#include "app/gui/fit_worker.h"
#include "app/gui/scene_loading.h"
#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/base/ms_since.h"
#include "core/mesh/chord_refinement.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/marching_memory.h"
#include "core/mesh/marching_squares.h"
#include "core/mesh/stray_pockets.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"

namespace hermite::app {

namespace {

// OBJ: `v x y 0` per point, one `l` element per polyline (closed ones repeat their first vertex).
std::string polylinesObj(const std::vector<Polyline2d>& lines) {
  std::string out = "# hermite-lab mesh: zero set of a 2D field, marching squares\n";
  char buf[96];
  for (const Polyline2d& l : lines)
    for (Eigen::Index i = 0; i < l.points.cols(); ++i) {
      std::snprintf(buf, sizeof buf, "v %.17g %.17g 0\n", l.points(0, i), l.points(1, i));
      out += buf;
    }
  long base = 1;
  for (const Polyline2d& l : lines) {
    out += 'l';
    for (Eigen::Index i = 0; i < l.points.cols(); ++i) {
      out += ' ';
      out += std::to_string(base + i);
    }
    if (l.closed) {
      out += ' ';
      out += std::to_string(base);
    }
    out += '\n';
    base += static_cast<long>(l.points.cols());
  }
  return out;
}

// SVG of the polylines over the box (y up in the data, down in SVG), stroke in data units.
std::string polylinesSvg(const std::vector<Polyline2d>& lines, const Box<2>& box) {
  const Vec<2> ext = box.extent();
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"%.17g %.17g %.17g %.17g\" width=\"800\" "
                "height=\"%.0f\">\n",
                box.lo.x(), -box.hi.y(), ext.x(), ext.y(), 800 * ext.y() / ext.x());
  std::string out = buf;
  std::snprintf(buf, sizeof buf, "<g fill=\"none\" stroke=\"black\" stroke-width=\"%.6g\">\n", 0.003 * ext.maxCoeff());
  out += buf;
  for (const Polyline2d& l : lines) {
    out += "<path d=\"";
    for (Eigen::Index i = 0; i < l.points.cols(); ++i) {
      std::snprintf(buf, sizeof buf, "%s%.9g %.9g ", i == 0 ? "M" : "L", l.points(0, i), -l.points(1, i));
      out += buf;
    }
    out += l.closed ? "Z\"/>\n" : "\"/>\n";
  }
  out += "</g>\n</svg>\n";
  return out;
}

std::string cellsText(const MarchingReport& r, int dim) {
  std::string s = std::to_string(r.cells[0]) + "x" + std::to_string(r.cells[1]);
  if (dim == 3) s += "x" + std::to_string(r.cells[2]);
  return s;
}

// Before the fit: the grid over view.bounds when the scene gives them; otherwise over the
// smallest box the default bounds can be (each side at least 1/3 of the longest: the samples'
// box grown by 25 % of its longest side on every side), so that no mesh that would fit is refused.
// marchingCubes checks the exact grid again once the bounds are known.
template <int Dim>
void checkMeshGrid(const Scene& scene, int resolution) {
  Box<Dim> box;
  if (scene.view.bounds) {
    box = viewBounds<Dim>(scene.view, Points<Dim>(Dim, 0));
  } else {
    box.lo.setZero();
    box.hi.setConstant(1.0);
    box.hi[Dim - 1] = 3.0;  // 3D slabs span x and y: the long side along z is the smallest plan
  }
  if constexpr (Dim == 3) checkMemory(marchingSlabPlan(box, resolution), kMarchingRemedy);  // streamed by slabs
  else checkMemory(marchingGridPlan<Dim>(box, resolution), kMarchingRemedy);
}

// What the contouring did beyond the uniform grid, appended to the summary line: about samples
// on parts thinner than a cell (MarchingOptions::anchors), and the open slivers it left out.
void appendContourText(const MarchingReport& r, char* line, std::size_t size) {
  using Refinement = MarchingReport::Refinement;
  std::size_t used = std::strlen(line);
  if (r.refinement == Refinement::Refined) {
    std::snprintf(line + used, size - used,
                  "; refined to %dx%dx%d cells at %d samples on parts thinner than a cell (%d still missed)",
                  r.refinedCells[0], r.refinedCells[1], r.refinedCells[2], r.missedAnchors, r.stillMissed);
  } else if (r.refinement != Refinement::None) {
    const char* why = r.refinement == Refinement::NoGain      ? " (a refined grid gave no fewer pieces)"
                      : r.refinement == Refinement::NotNearer ? " (a refined grid lay no nearer them)"
                      : r.refinement == Refinement::TooLarge  ? ", too many to refine the grid at: raise --resolution"
                                                              : "";
    std::snprintf(line + used, size - used, "; %d samples on parts thinner than a cell lie off the mesh%s",
                  r.missedAnchors, why);
  }
  used = std::strlen(line);
  if (r.droppedSlivers > 0)
    std::snprintf(line + used, size - used, "; %d open pieces smaller than a cell face left out", r.droppedSlivers);
  used = std::strlen(line);
  if (r.droppedTips > 0)
    std::snprintf(line + used, size - used, "; %d tips of parts thinner than a cell, cut off by the grid, left out",
                  r.droppedTips);
  used = std::strlen(line);
  if (r.droppedGaps > 0)
    std::snprintf(line + used, size - used,
                  "; %d pockets of gaps thinner than a cell, enclosed by the grid, left out", r.droppedGaps);
  used = std::strlen(line);
  if (r.centresOffZeroSet > 0)
    std::snprintf(line + used, size - used,
                  "; %d polygon centres with no root of f in their cube, left at their polygon's mean",
                  r.centresOffZeroSet);
}

// What the winding-number check did (stray_pockets.h), appended to the summary line.
void appendStrayText(const StrayReport& r, char* line, std::size_t size) {
  std::size_t used = std::strlen(line);
  if (r.tooMany)
    std::snprintf(line + used, size - used,
                  "; %d vertices strayed from the samples to where their winding number decides the side, too many "
                  "to trust it: left as they are",
                  r.strayVertices);
  else if (r.rounds > 0)
    std::snprintf(line + used, size - used,
                  "; %d vertices strayed from the samples to where their winding number decides the side: "
                  "contoured %d more time%s with that side",
                  r.strayVertices, r.rounds, r.rounds == 1 ? "" : "s");
  used = std::strlen(line);
  if (r.droppedPieces > 0)
    std::snprintf(line + used, size - used, "; %d pieces off the samples' surface (by winding number) left out",
                  r.droppedPieces);
}

}  // namespace

int autoMeshResolution(int dimension, long long samples) {
  if (dimension != 3) return 64;
  const double r = std::round(0.6 * std::sqrt(double(std::max(samples, 0LL))));
  return static_cast<int>(std::clamp(r, 64.0, double(kAutoMeshResolutionMax)));
}

// The mesh's closedness in words: a degenerate field's mesh is never called a closed manifold (its
// components may be noise, docs/maths.md "Degenerate fields"); a field with "no data" regions (a
// partition of unity) may also end where its data ends.
const char* degenerateText(bool degenerate, bool closedManifold, bool everywhereValid) {
  if (degenerate)
    return closedManifold ? "closed, but the field is degenerate (components may be noise)"
                          : "open (degenerate regions left out)";
  if (closedManifold) return "closed manifold";
  return everywhereValid ? "open (the surface leaves view.bounds)"
                         : "open (the surface leaves view.bounds or ends where the field has no data)";
}

namespace {

// The 3D branch of exportZeroSet: contours, refines chords, saves, and writes the summary line
// (without the output path) into `line`.
void exportZeroSet3d(const SceneFit<3>& f3, const Box<3>& bounds, MarchingOptions options, double chordTolerance,
                     const std::string& output, char* line, std::size_t size) {
  options.anchors = &f3.data.points;  // the samples the model interpolates lie on its zero set
  MarchingReport report;
  StrayReport stray;
  std::unique_ptr<ImplicitField<3>> guarded;  // the field as the contour read it, when guarded
  const auto start = std::chrono::steady_clock::now();
  TriMesh mesh = contourWithoutStrays(f3.field(), bounds, options, f3.data, &report, &stray, &guarded);
  const double contourMs = msSince(start);
  const ImplicitField<3>& field = guarded ? *guarded : f3.field();
  ChordRefinementReport chords;
  if (chordTolerance > 0) {
    ChordRefinementOptions co;
    co.cancel = options.cancel;
    co.tolerance = chordTolerance * bounds.extent().maxCoeff() / options.resolution;  // cells → world units
    // New vertices where the review would see strays leave their edges whole (stray.planes is
    // null where no review ran or it found too many strays to trust the winding number).
    if (const std::shared_ptr<const StrayTest> planes = stray.planes)
      co.rejects = [planes](const Points<3>& X) { return (*planes)(X); };
    mesh = refineChords(mesh, field, co, &chords);
  }
  saveMesh(output, mesh);
  // Degenerate: far smaller than the triangles a vertex 10⁻³ of an edge from a grid point makes.
  const double tiny = std::min(1e-9 * report.minStep * report.minStep, 1e-12 * bounds.extent().squaredNorm());
  const MeshCheck c = checkMesh(mesh, tiny, false);  // the summary names no piece count
  // A degenerate field's flat regions are "no data": what is left is not closed over them.
  const bool degenerate = f3.degenerateField && f3.degenerateField->degenerate;
  std::snprintf(line, size,
                "mesh: %d vertices, %d triangles, %s, Euler characteristic %d; %s cells, max |f| %.3g; "
                "%.1f ms (field %.1f ms)",
                mesh.vertexCount(), mesh.triangleCount(),
                degenerateText(degenerate, mesh.triangleCount() > 0 && c.closedManifold(),
                               f3.field().everywhereValid()),
                c.eulerCharacteristic, cellsText(report, 3).c_str(), std::max(report.maxAbsF, chords.maxAbsF),
                contourMs + chords.ms, report.evaluateMs);
  appendContourText(report, line, size);
  appendStrayText(stray, line, size);
  if (chordTolerance > 0) {
    // The total above includes the chord refinement; its own share, after it.
    const std::size_t used = std::strlen(line);
    std::snprintf(line + used, size - used, "; %d edges split by chord refinement (%d left whole), %.1f ms",
                  chords.splitEdges, chords.unsplitEdges, chords.ms);
  }
  std::strncat(line, " -> ", size - std::strlen(line) - 1);
}

}  // namespace

std::string exportZeroSet(const FitOutcome& fit, const std::string& output, int resolution, double chordTolerance,
                          const CancelToken* cancel) {
  const Scene& scene = fit.scene;
  const int dim = scene.dimension();
  const std::string ext = dim == 3 ? requireExtension("mesh", output, {"glb", "gltf", "ply", "obj"})
                                   : requireExtension("mesh", output, {"obj", "svg"});
  requireWritableLocation("mesh", output);
  MarchingOptions options;
  options.resolution = resolution;
  options.cancel = cancel;
  MarchingReport report;
  // Room for every clause at once with 10-digit counts (about 900 characters).
  char line[2048];
  if (const SceneFit<3>* f3 = fit.as<SceneFit<3>>()) {
    exportZeroSet3d(*f3, viewBounds<3>(scene.view, f3->data.points), options, chordTolerance, output, line,
                    sizeof line);
  } else if (const SceneFit<2>* f2 = fit.as<SceneFit<2>>()) {
    const Box<2> bounds = viewBounds<2>(scene.view, f2->data.points);
    const std::vector<Polyline2d> lines = marchingSquares(f2->field(), bounds, options, &report);
    writeFileAtomically(output, ext == "svg" ? polylinesSvg(lines, bounds) : polylinesObj(lines));
    int closed = 0;
    Eigen::Index points = 0;
    for (const Polyline2d& l : lines) {
      closed += l.closed;
      points += l.points.cols();
    }
    std::snprintf(line, sizeof line,
                  "mesh: %zu polylines (%d closed), %ld points; %s cells, max |f| %.3g; %.1f ms -> ", lines.size(),
                  closed, static_cast<long>(points), cellsText(report, 2).c_str(), report.maxAbsF, report.totalMs);
  } else {
    throw InputError("mesh: mode '" + std::string(sceneModeName(scene.mode)) + "' has no implicit to mesh");
  }
  return std::string(line) + output;
}

int runMesh(const MeshArgs& args) {
  const Scene scene = loadCommandScene(args.scene);
  // Check the output before the (possibly long) fit.
  if (scene.dimension() == 3) {
    requireExtension("mesh", args.output, {"glb", "gltf", "ply", "obj"});
  } else {
    try {
      requireExtension("mesh", args.output, {"obj", "svg"});
    } catch (const UsageError& e) {  // a 2D file (two numbers a line) is easily taken for 3D data
      throw UsageError(std::string(e.what()) + ": " + scene.sourceName + " is 2D data, whose zero set is polylines");
    }
  }
  requireWritableLocation("mesh", args.output);
  // Before the fit the sample count is not known: the automatic resolution is checked at its largest.
  const int planned = args.resolution > 0 ? args.resolution : autoMeshResolution(scene.dimension(), LLONG_MAX);
  if (scene.mode == SceneMode::Implicit3d) checkMeshGrid<3>(scene, planned);
  if (scene.mode == SceneMode::Implicit2d) checkMeshGrid<2>(scene, planned);
  std::string summary;
  std::shared_ptr<const FitOutcome> fit;
  {
    const TerminalProgress progress("fitting and meshing " + scene.sourceName);
    fit = fitOutcomeOrThrow(scene);
    const int resolution =
        args.resolution > 0 ? args.resolution : autoMeshResolution(scene.dimension(), fit->dataCount());
    summary = exportZeroSet(*fit, args.output, resolution, args.chordTolerance);
  }
  writeStdout(summary + "\n");
  if (const SceneFitReport* f = fit->implicitFit()) printDataWarnings(*f);
  // A degenerate field's flat regions are left out of the mesh (no data); say why it is open.
  for (const std::string& w : fit->warnings())
    if (w.rfind(kDegenerateFieldWarningStart, 0) == 0) std::cerr << "warning: " << w << "\n";
  keepUntilExit(std::move(fit));  // the process ends next: freeing the local models one by one only costs time
  return 0;
}

}  // namespace hermite::app
