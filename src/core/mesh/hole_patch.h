#pragma once
// The triangles and new vertices that close one hole, as each hole-filling stage leaves them.

#include <string>

#include <Eigen/Core>

#include "core/mesh/tri_mesh.h"

namespace hermite {

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
  bool graded = false;            // refined with sizes growing inside (patch_refinement.h)
  double rimFold = 0;             // > 0: the patch meets the mesh in a thin wedge (median angle, radians)
  bool closed = false;            // the front closed within its bound
  std::string failure;            // why not, when not closed
  int frontSteps = 0;
};

}  // namespace hermite
