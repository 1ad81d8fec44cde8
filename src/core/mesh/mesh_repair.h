#pragma once
// What hole filling checks and mends in its input before looking for holes: duplicate faces,
// triangles oriented against their neighbours, edges shared by more than two triangles.

#include <string>
#include <vector>

#include "core/mesh/tri_mesh.h"

namespace hermite {

struct MeshRepairReport {
  int weldedVertices = 0;           // vertices at exactly the position of an earlier one, merged into it
  int collapsedFaces = 0;           // triangles left with a repeated vertex by the welding: dropped
  int duplicateFaces = 0;           // dropped: the same three vertices as an earlier triangle
  int reorientedFaces = 0;          // turned to agree with their edge-connected neighbours
  int nonManifoldEdges = 0;         // edges of three or more triangles: reported, left as they are
  int nonOrientableComponents = 0;  // components no orientation makes consistent (a Möbius strip)
  std::vector<std::string> messages;
  bool clean() const {
    return weldedVertices == 0 && collapsedFaces == 0 && duplicateFaces == 0 && reorientedFaces == 0 && nonManifoldEdges == 0 && nonOrientableComponents == 0;
  }
};

// The mesh with vertices at identical positions welded (triangles use the first of them; the
// others stay, unused, so ids keep their meaning), triangles that collapse or repeat another
// dropped, and each orientable component's triangles turned the way most of them already face
// (neighbours across two-triangle edges must traverse the edge in opposite directions).
// Unambiguous problems are mended; the rest are counted in `report` with a message each.
TriMesh repairMesh(const TriMesh& mesh, MeshRepairReport& report);

}  // namespace hermite
