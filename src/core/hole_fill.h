#pragma once
// Hole filling of triangle meshes with RBF implicits (issue 8 §3). Each stage is a function of
// its own returning its intermediate result, so the GUI can show the pipeline step by step:
//
//   1. detectHoles      boundary edges chained into ordered loops (tri_mesh.h boundaryLoops);
//   2. advancingFront   the minimum-angle advancing front: an initial patch of new vertices and
//                       triangles (Zhao, Gao & Lin 2007, "A robust hole-filling algorithm");
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

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/radial_sum.h"
#include "core/tri_mesh.h"

namespace hermite {

enum class HoleImplicitKind { RbfOffset, Hrbf };

struct HoleFillOptions {
  // Advancing front: at most frontStepFactor · (n²/4 + 40n) + 10 steps for n boundary edges, then
  // the hole is reported as not closed (a bound, never a hang).
  double frontStepFactor = 1.0;
  // A new vertex closer than this × l to another front vertex is merged with it (the front splits).
  double mergeDistance = 1.0;
  int clipFrontSize = 6;  // fronts of at most this many vertices are closed by clipping (no new vertices)
  // fillHoles: when a front does not close, retry with these (mergeDistance, clipFrontSize) pairs
  // before reporting the hole (a front that wraps around a strongly curved part can fold).
  std::vector<std::pair<double, int>> frontRetries{{0.8, 8}, {0.6, 10}, {1.2, 4}};
  bool fair = true;
  bool fitAndProject = true;          // stages 4–5 (off: the faired patch is the result)
  int rings = 2;                      // rings of vertices around the hole given to the fit (≥ 1)
  int maxFitSamples = 600;            // ring vertices beyond this are subsampled (dense solve)
  double offsetFraction = 0.05;       // d = this × hole diameter (RBF with offsets)
  HoleImplicitKind implicit = HoleImplicitKind::RbfOffset;
  int newtonIterations = 20;          // per vertex
  double newtonTolerance = 1e-7;      // step length below this × hole diameter: converged
};

// The original mesh with what every stage looks up: vertex → triangles (CSR) and area-weighted
// vertex normals. Build once per mesh; holds a reference to it.
class PreparedMesh {
 public:
  explicit PreparedMesh(const TriMesh& mesh);
  const TriMesh& mesh() const { return *mesh_; }
  const Eigen::Matrix3Xd& normals() const { return normals_; }  // 3 × V
  // Triangles incident to vertex v.
  const int* trianglesBegin(int v) const { return triangles_.data() + offsets_[v]; }
  const int* trianglesEnd(int v) const { return triangles_.data() + offsets_[v + 1]; }
  // Vertices sharing an edge with v (sorted, unique).
  std::vector<int> neighbours(int v) const;

 private:
  const TriMesh* mesh_;
  Eigen::Matrix3Xd normals_;
  std::vector<int> offsets_;    // V + 1
  std::vector<int> triangles_;  // incident triangle ids, grouped by vertex
};

// 1. The holes: boundaryLoops(mesh) (each loop in the triangles' direction, hole on its right).
std::vector<BoundaryLoop> detectHoles(const TriMesh& mesh);

// A patch closing one hole. New vertex k has id baseId + k, where baseId = mesh.vertexCount() of
// the original mesh; patch triangles use original and new ids, counter-clockwise from outside.
struct HolePatch {
  BoundaryLoop loop;              // the hole, as detectHoles returned it
  int baseId = 0;                 // id of the first new vertex
  Eigen::Matrix3Xd vertices;      // 3 × K new vertex positions
  Eigen::Matrix3Xi triangles;     // 3 × T
  Eigen::Matrix3Xd vertexNormals; // 3 × K normals guessed by the front (its local surface normals)
  double meanEdgeLength = 0;      // l of the boundary
  double diameter = 0;            // largest distance between two boundary vertices
  bool closed = false;            // the front closed within its bound
  std::string failure;            // why not, when not closed
  int frontSteps = 0;
};

// 2. The minimum-angle advancing front. Angles are in [0, 2π), measured on the hole's side about
// the local surface normal; < 75°: one triangle; 75°–135°: one new vertex at distance l along the
// bisector, two triangles; > 135°: two new vertices at thirds of the angle, three triangles.
// Safeguards that keep it from folding: a new vertex within mergeDistance·l of another front
// vertex is replaced by that vertex (the front splits in two, each closed in turn); a step whose
// new edges would repeat an edge or cross the front (in the vertex's tangent plane) is not taken
// (the next smallest angle is tried); fronts of ≤ clipFrontSize vertices are closed by clipping.
// Bounded: at most frontStepFactor · (n²/4 + 40n) + 10 steps, and a front that grows past 2n + 10 vertices
// (or n²/4 + 4n new ones) has folded — both end with `closed` false and the reason in `failure`.
HolePatch advancingFront(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options = {});

// 3. Least-squares-mesh fairing (uniform Laplacian rows for the new vertices and the boundary
// vertices, boundary fixed), solved by a sparse Cholesky factorisation of the normal equations.
// Returns the patch with moved vertices (unchanged when it has none). NumericalError if the solve fails.
HolePatch fairPatch(const PreparedMesh& prepared, const HolePatch& patch);

// 4. The implicit around a hole, with the samples it was fitted to (for display).
struct HoleImplicit {
  std::unique_ptr<RadialSum<3>> field;
  Points<3> points;        // 3 × S ring vertices used
  Points<3> normals;       // 3 × S their unit normals
  double offset = 0;       // d (RBF with offsets)
  HoleImplicitKind kind = HoleImplicitKind::RbfOffset;
};
HoleImplicit fitHoleImplicit(const PreparedMesh& prepared, const HolePatch& patch, const HoleFillOptions& options = {});

// 5. Newton projection of the new vertices onto f = 0. A step that would flip a patch triangle
// (its normal turning by more than 90° from the unprojected patch) or make it degenerate is halved
// up to 4 times, then the vertex stops; a vertex that has not converged within the iteration bound
// returns to its faired position and is counted.
struct ProjectionResult {
  HolePatch patch;
  int unconverged = 0;
  double maxAbsF = 0;  // max |f| over the new vertices after projection
};
ProjectionResult projectPatch(const PreparedMesh& prepared, const HolePatch& patch, const ImplicitField<3>& field,
                              const HoleFillOptions& options = {});

// How far fillHole goes: the GUI's holefill mode stops at each stage in turn; fillHoles goes to
// the end.
enum class HoleFillStage { Holes, Front, Fair, Fit, Project };

// One hole through the stages up to `last` (front with its retries, fairing, implicit fit,
// projection — as the options enable them). Never throws: what went wrong is in `notes`, each
// starting with `name`.
struct HoleOutcome {
  HolePatch patch;           // as the last stage left it (the unclosed front when not filled)
  Points<3> ringPoints;      // Fit and later: the samples of the implicit
  Points<3> ringNormals;
  bool filled = false;       // the front closed and the stages ran
  int unconverged = 0;       // Project: vertices left at their faired position
  double maxAbsF = 0;        // Project: max |f| over the new vertices
  std::vector<std::string> notes;
};
HoleOutcome fillHole(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options,
                     HoleFillStage last = HoleFillStage::Project, const std::string& name = "hole");

// `mesh` with the patches' new vertices appended after its own (consecutive ids, in order) and
// their triangles after its triangles; normals are not set.
TriMesh appendPatches(const TriMesh& mesh, const std::vector<const HolePatch*>& patches);

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
};
HoleFillResult fillHoles(const TriMesh& mesh, const HoleFillOptions& options = {});

}  // namespace hermite
