// `hermite-lab holefill IN -o OUT [--json] [--allow-open]` (docs/cli.md): fills the holes of a
// triangle mesh (core/mesh/hole_fill.h) and reports each hole, what was mended in the input, the
// largest |f| after projection, vertices that did not converge, and the time. Exit 5 when the
// output is written but a hole stays open (unless --allow-open).

#include <unistd.h>

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "app/commands/output_path.h"
#include "core/mesh/hole_fill.h"
#include "io/mesh_file.h"

namespace hermite::app {

namespace {

constexpr int kIncomplete = 5;  // output written, but a hole stays open

nlohmann::json holesJson(const HoleFillResult& r) {
  nlohmann::json holes = nlohmann::json::array();
  for (const HoleReport& h : r.holes)
    holes.push_back({{"edges", h.edges},
                     {"method", h.method.empty() ? nlohmann::json(nullptr) : nlohmann::json(h.method)},
                     {"filled", h.filled},
                     {"reason", h.filled ? nlohmann::json(nullptr) : nlohmann::json(h.reason)}});
  return holes;
}

nlohmann::json repairJson(const MeshRepairReport& r) {
  return {{"welded_vertices", r.weldedVertices},
          {"collapsed_faces", r.collapsedFaces},
          {"duplicate_faces", r.duplicateFaces},
          {"reoriented_faces", r.reorientedFaces},
          {"non_manifold_edges", r.nonManifoldEdges},
          {"non_orientable_components", r.nonOrientableComponents}};
}

std::string textReport(const HoleFillArgs& args, const HoleFillResult& r, const MeshCheck& c) {
  char line[512];
  std::snprintf(line, sizeof line,
                "holes found:      %d\nholes filled:     %d\ntriangles added:  %d\nmax |f|:          %.3g (after "
                "projection, %s implicit)\nunconverged:      %d vertices\ntime:             %.1f ms\nresult:           "
                "%d vertices, %d triangles, %s -> ",
                r.holesFound, r.holesFilled, r.trianglesAdded, r.maxAbsF, args.implicit.c_str(), r.unconverged, r.ms,
                r.mesh.vertexCount(), r.mesh.triangleCount(),
                c.closedManifold() ? "closed manifold" : (c.closed() ? "closed" : "still open"));
  std::string text = line;
  text += args.output + "\n";
  for (std::size_t h = 0; h < r.holes.size(); ++h) {
    const HoleReport& hole = r.holes[h];
    text += "hole " + std::to_string(h) + ":           " + std::to_string(hole.edges) + " edges, " +
            (hole.method.empty() ? std::string("-") : hole.method) + ", " +
            (hole.filled ? std::string("filled") : "open: " + hole.reason) + "\n";
  }
  for (const std::string& m : r.messages) text += "note: " + m + "\n";
  return text;
}

// Progress on stderr when it is a terminal: "holefill: 40 %", rewritten in place when the
// percentage changes (the stages report hundreds of times per large hole).
void showProgress(double fraction) {
  static int shown = -1;
  const int percent = int(fraction * 100.0 + 0.5);
  if (percent == shown) return;
  shown = percent;
  std::fprintf(stderr, "\rholefill: %3d %%", percent);
  if (percent >= 100) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace

int runHoleFill(const HoleFillArgs& args) {
  requireExtension("holefill", args.output, {"glb", "gltf", "ply", "obj"});
  requireWritableLocation("holefill", args.output);
  const TriMesh mesh = loadMesh(args.input);
  HoleFillOptions options;
  options.rings = args.rings;
  options.implicit = args.implicit == "hrbf" ? HoleImplicitKind::Hrbf : HoleImplicitKind::RbfOffset;
  if (isatty(STDERR_FILENO)) options.progress = [](double f) { return showProgress(f), true; };
  const HoleFillResult r = fillHoles(mesh, options);
  saveMesh(args.output, r.mesh);
  const MeshCheck c = checkMesh(r.mesh);
  const bool complete = r.holesFilled == r.holesFound && c.closed();
  if (args.json) {
    nlohmann::json j = {{"holes_found", r.holesFound},     {"holes_filled", r.holesFilled},
                        {"triangles_added", r.trianglesAdded}, {"max_abs_f", r.maxAbsF},
                        {"unconverged", r.unconverged},     {"ms", r.ms},
                        {"implicit", args.implicit},        {"closed", c.closed()},
                        {"messages", r.messages},           {"holes", holesJson(r)},
                        {"repairs", repairJson(r.repair)},  {"complete", complete}};
    writeStdout(j.dump(2) + "\n");
  } else {
    writeStdout(textReport(args, r, c));
  }
  if (!complete && !args.allowOpen) {
    std::fprintf(stderr, "holefill: %s written, but %d of %d holes stay open%s (exit 5; --allow-open accepts it)\n",
                 args.output.c_str(), r.holesFound - r.holesFilled, r.holesFound,
                 c.closed() ? "" : " and the result has boundary edges");
    return kIncomplete;
  }
  return 0;
}

}  // namespace hermite::app
