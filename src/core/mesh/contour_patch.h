#pragma once
// Contouring part of a grid again (docs/maths.md, "Stray pockets"): where a field changes only
// inside some blocks of a grid's cells (a winding guard about a few strays), the contour of the
// changed field is the old contour with those blocks' triangles replaced by a pass over the
// blocks alone. Marching cubes decides every vertex from its grid edge's two values and every face
// from its four (and, when ambiguous, f at a point of the face they fix: face_decider.h), so on a
// block's faces, where the field is unchanged, the pass makes exactly the
// old contour's vertices: the new triangles are joined to the old ones through them (matched by
// grid edge), and the mesh stays watertight.

#include <array>
#include <optional>
#include <vector>

#include "core/base/implicit_field.h"
#include "core/mesh/grid_lines.h"
#include "core/mesh/marching_options.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

// Cells [lo[a], hi[a]) along each axis of a grid.
struct CellBlock {
  std::array<int, 3> lo{}, hi{};
};

// The cells within `reach` (world units) of each centre, plus one cell on every side, as blocks
// on `lines`; blocks that overlap or touch are merged into their bounding block until none do.
std::vector<CellBlock> cellBlocksAround(const GridLines<3>& lines, const std::vector<Vec<3>>& centres, double reach);

// `mesh` (marching cubes' contour on `lines`, uniform cell `h`) with the cells of `blocks`
// (disjoint, not touching) contoured again with `field`, which must equal the old field outside
// them, then reviewed as options.review says and its open slivers left out (open_slivers.h), as
// marchingCubes does. A vertex the passes make on a block's face without
// an old twin belongs to a piece the old contour's review left out; the review must leave it out
// again. Null when a seam stays open — an old vertex without a new twin, or such a vertex left
// after the review: the caller contours the whole grid instead.
std::optional<TriMesh> patchContour(const TriMesh& mesh, const ImplicitField<3>& field, const GridLines<3>& lines,
                                    const Vec<3>& h, const std::vector<CellBlock>& blocks,
                                    const MarchingOptions& options);

}  // namespace hermite
