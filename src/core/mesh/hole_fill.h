#pragma once
// Hole filling of triangle meshes with RBF implicits. Each stage is a function of
// its own returning its intermediate result, so the GUI can show the pipeline step by step:
//
//   1. detectHoles      boundary edges chained into ordered loops (tri_mesh.h boundaryLoops);
//   2. advancingFront   the minimum-angle advancing front: an initial patch of new vertices and
//                       triangles (Zhao, Gao & Lin 2007, "A robust hole-filling algorithm");
//                       where it fails, or for holes too large for it, minWeightPatch: the
//                       minimum-weight triangulation of the boundary (Liepa 2003), refined;
//   3. fairPatch        least-squares mesh (Sorkine & Cohen-Or 2004): the new vertices minimise
//                       Σ‖L x‖² with the uniform Laplacian L, original vertices fixed;
//   4. fitHoleImplicit  an implicit through `rings` rings of vertices around the hole: values 0
//                       and ±d along the vertex normals (RBF with offsets, x³ + linear), or an
//                       HRBF on the same vertices with their normals;
//   5. projectPatch     Newton x ← x − f∇f/‖∇f‖² on every new vertex, rejecting steps that flip a
//                       patch triangle.
// fillHoles runs them all (retrying a front that does not close with other safeguard settings). Where the input is closed apart from its holes, the output is a closed,
// consistently oriented 2-manifold without degenerate or flipped triangles (holes whose front does
// not close are reported and left open).

#include <string>
#include <vector>

#include "core/mesh/advancing_front.h"
#include "core/mesh/hole_fairing.h"
#include "core/mesh/hole_fill_options.h"
#include "core/mesh/hole_implicit.h"
#include "core/mesh/hole_patch.h"
#include "core/mesh/mesh_repair.h"
#include "core/mesh/prepared_mesh.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// 1. The holes: boundaryLoops(mesh) (each loop in the triangles' direction, hole on its right).
std::vector<BoundaryLoop> detectHoles(const TriMesh& mesh);

// How far fillHole goes: the GUI's holefill mode stops at each stage in turn; fillHoles goes to
// the end.
enum class HoleFillStage { Holes, Front, Fair, Fit, Project };

// One hole through the stages up to `last` (front with its retries, fairing, implicit fit,
// projection — as the options enable them). Never throws: what went wrong is in `notes`, each
// starting with `name`.
struct HoleOutcome {
  HolePatch patch;           // as the last stage left it (the unclosed front when not filled)
  std::string method;        // "front" or "min-weight": what made the first patch
  std::string reason;        // why not filled (empty when filled)
  Points<3> ringPoints;      // Fit and later: the samples of the implicit
  Points<3> ringNormals;
  Eigen::Matrix3Xd unprojected;  // the patch's vertices before projection (after fairing)
  bool filled = false;       // the front closed and the stages ran
  bool cancelled = false;    // options.progress returned false (reason "cancelled")
  int unconverged = 0;       // Project: vertices left at their faired position
  double maxAbsF = 0;        // Project: max |f| over the new vertices
  std::vector<std::string> notes;
};
HoleOutcome fillHole(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options,
                     HoleFillStage last = HoleFillStage::Project, const std::string& name = "hole");

// `mesh` with the patches' new vertices appended after its own (consecutive ids, in order) and
// their triangles after its triangles; normals are not set.
TriMesh appendPatches(const TriMesh& mesh, const std::vector<const HolePatch*>& patches);

// One hole in `holefill --json`'s `holes` list.
struct HoleReport {
  int edges = 0;
  std::string method;  // "front" or "min-weight"
  bool filled = false;
  std::string reason;  // empty when filled
};

// Everything: the filled mesh and what `holefill --json` reports.
struct HoleFillResult {
  TriMesh mesh;                       // input vertices first (same ids), then the patches'
  int holesFound = 0;
  int holesFilled = 0;
  int trianglesAdded = 0;
  double maxAbsF = 0;                 // over all projected vertices
  int unconverged = 0;
  double ms = 0;
  std::vector<std::string> messages;  // holes not filled and why
  std::vector<HoleReport> holes;      // one per hole found, in detectHoles order
  MeshRepairReport repair;            // what was mended in the input first (mesh_repair.h)
  bool cancelled = false;             // options.progress returned false
};
// The input is first mended (repairMesh: duplicate faces dropped, orientation made consistent);
// the result's mesh has the mended triangles, then the patches'.
HoleFillResult fillHoles(const TriMesh& mesh, const HoleFillOptions& options = {});

}  // namespace hermite
