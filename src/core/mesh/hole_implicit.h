#pragma once
// Stages 4–5 of hole filling (hole_fill.h): the implicit around a hole and the projection of the
// patch onto its zero set.

#include <memory>

#include "core/base/implicit_field.h"
#include "core/mesh/hole_fill_options.h"
#include "core/mesh/hole_patch.h"
#include "core/mesh/prepared_mesh.h"
#include "core/rbf/radial_sum.h"

namespace hermite {

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
// returns to its faired position and is counted. options.progress (optional) receives the
// fraction of the sweeps done every 256 vertices; false from it stops the projection.
struct ProjectionResult {
  HolePatch patch;
  int unconverged = 0;
  double maxAbsF = 0;  // max |f| over the new vertices after projection
  bool cancelled = false;  // options.progress returned false: the patch is half projected
};
ProjectionResult projectPatch(const PreparedMesh& prepared, const HolePatch& patch, const ImplicitField<3>& field,
                              const HoleFillOptions& options = {});

}  // namespace hermite
