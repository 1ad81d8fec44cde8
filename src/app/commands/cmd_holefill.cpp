// `hermite-lab holefill IN -o OUT [--json]` (docs/cli.md): fills the holes of a triangle mesh
// (core/hole_fill.h) and reports holes found and filled, triangles added, the largest |f| after
// projection, vertices that did not converge, and the time.

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "app/commands/output_path.h"
#include "core/mesh/hole_fill.h"
#include "io/mesh_file.h"

namespace hermite::app {

int runHoleFill(const HoleFillArgs& args) {
  requireExtension("holefill", args.output, {"glb", "gltf", "ply", "obj"});
  requireWritableLocation("holefill", args.output);
  const TriMesh mesh = loadMesh(args.input);
  HoleFillOptions options;
  options.rings = args.rings;
  options.implicit = args.implicit == "hrbf" ? HoleImplicitKind::Hrbf : HoleImplicitKind::RbfOffset;
  const HoleFillResult r = fillHoles(mesh, options);
  saveMesh(args.output, r.mesh);
  const MeshCheck c = checkMesh(r.mesh);
  if (args.json) {
    nlohmann::json j = {{"holes_found", r.holesFound},     {"holes_filled", r.holesFilled},
                        {"triangles_added", r.trianglesAdded}, {"max_abs_f", r.maxAbsF},
                        {"unconverged", r.unconverged},     {"ms", r.ms},
                        {"implicit", args.implicit},        {"closed", c.closed()},
                        {"messages", r.messages}};
    writeStdout(j.dump(2) + "\n");
    return 0;
  }
  char line[512];
  std::snprintf(line, sizeof line,
                "holes found:      %d\nholes filled:     %d\ntriangles added:  %d\nmax |f|:          %.3g (after "
                "projection, %s implicit)\nunconverged:      %d vertices\ntime:             %.1f ms\nresult:           "
                "%d vertices, %d triangles, %s -> ",
                r.holesFound, r.holesFilled, r.trianglesAdded, r.maxAbsF, args.implicit.c_str(), r.unconverged, r.ms,
                r.mesh.vertexCount(), r.mesh.triangleCount(),
                c.closedManifold() ? "closed manifold" : (c.closed() ? "closed" : "still open"));
  std::string text = line;
  text += args.output;
  text += '\n';
  for (const std::string& m : r.messages) text += "note: " + m + "\n";
  writeStdout(text);
  return 0;
}

}  // namespace hermite::app
