#pragma once
// Triangle meshes: vertices, triangles, per-vertex normals, and the topology
// queries hole filling and the loaders need (boundary loops, connected components).
// Orientation: triangles are counter-clockwise seen from outside, so the face normal
// (v1 − v0) × (v2 − v0) points outward (the same side as ∇f of an implicit, docs/maths.md, Conventions).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/base/geometry.h"

namespace hermite {

struct TriMesh {
  Eigen::Matrix3Xd vertices;   // 3 × V, one vertex per column
  Eigen::Matrix3Xi triangles;  // 3 × T, vertex indices, counter-clockwise from outside
  Eigen::Matrix3Xd normals;    // 3 × V unit vertex normals, or 3 × 0 when the mesh has none; a mesh
                               // read from a file has a zero column where the file's normal is zero

  int vertexCount() const { return static_cast<int>(vertices.cols()); }
  int triangleCount() const { return static_cast<int>(triangles.cols()); }
  bool hasNormals() const { return normals.cols() == vertices.cols() && vertices.cols() > 0; }
};

// ---- topology ------------------------------------------------------------------------------

// One boundary loop: vertex indices in order, following the directed boundary edges as the
// triangles use them (each consecutive pair (vᵢ, vᵢ₊₁), wrapping around, is an edge of exactly one
// triangle, traversed in that triangle's counter-clockwise order; the hole lies on its right).
using BoundaryLoop = std::vector<int>;

// Boundary edges (used by exactly one triangle) chained into ordered loops. A vertex where
// several boundary loops touch (a "figure-eight") is visited once per loop: loops are split there
// so each returned loop is simple (no repeated vertex). Edges used by three or more triangles are
// not boundary edges. Triangles must reference valid vertices.
std::vector<BoundaryLoop> boundaryLoops(const TriMesh& mesh);

// Component index (0-based, in order of first triangle) per triangle, triangles connected when
// they share an edge; `count` receives the number of components when not null, `open` (when not
// null) one flag per component: 1 when one of its edges belongs to a single triangle.
std::vector<int> triangleComponents(const TriMesh& mesh, int* count = nullptr, std::vector<char>* open = nullptr);

// Number of connected components of the mesh's triangles (edge-connected).
int connectedComponentCount(const TriMesh& mesh);

// Number of components of triangles connected through shared vertices: one union-find pass, no
// sort. Equals connectedComponentCount where each vertex's triangles form one fan (marching
// cubes' output); smaller where pieces only touch at a vertex.
int vertexConnectedComponentCount(const TriMesh& mesh);
// The piece of each triangle (0 … count − 1, numbered in order of first triangle) by the same
// vertex union-find; *count (when not null) receives their number.
std::vector<int> vertexConnectedComponents(const TriMesh& mesh, int* count = nullptr);

// A mesh's pieces by vertexConnectedComponents, their sizes and the largest (marching cubes'
// pieces meet at no vertex, so this finds them without an edge sort).
struct MeshPieces {
  std::vector<int> of;    // per triangle: its piece
  std::vector<int> size;  // per piece: its triangles
  int largest = -1;       // the piece with the most triangles (the first of them on a tie); −1: none
  explicit MeshPieces(const TriMesh& mesh);
  int count() const { return static_cast<int>(size.size()); }
};

// Removes the vertices no triangle uses (and their normals), renumbering the triangles; the rest
// keep their order.
void dropUnusedVertices(TriMesh& mesh);

// Per vertex, the smallest vertex id at exactly its position (itself when no earlier vertex is
// there): what welding merges each vertex into.
std::vector<int> coincidentVertexRoots(const TriMesh& mesh);
// The same from the vertices' lexicographicOrder (core/points/lexicographic_order.h), for a caller
// that sorts them for something else too.
std::vector<int> coincidentVertexRoots(const TriMesh& mesh, const std::vector<Eigen::Index>& order);

// Removes the triangles of every component c with drop[c] set (label: a component per triangle,
// as triangleComponents or vertexConnectedComponents give), then the vertices no triangle uses;
// the rest keep their order. Returns how many components were removed.
int dropComponents(TriMesh& mesh, const std::vector<int>& label, const std::vector<char>& drop);

// The bounding box of each of the `count` components (`label`: one per triangle, as for
// dropComponents).
std::vector<Box<3>> componentBoxes(const TriMesh& mesh, const std::vector<int>& label, int count);

// ---- normals -------------------------------------------------------------------------------

enum class NormalWeighting { Area, Angle };

// Unit vertex normals (3 × V) as the weighted mean of the incident face normals (area: the
// unnormalised cross product; angle: the corner angle times the unit face normal). A vertex with
// no triangle, or whose weighted sum vanishes, gets (0, 0, 0).
Eigen::Matrix3Xd vertexNormals(const TriMesh& mesh, NormalWeighting weighting = NormalWeighting::Area);

// ---- checks --------------------------------------------------------------------------------

struct MeshCheck {
  int boundaryEdges = 0;       // undirected edges used by exactly one triangle
  int nonManifoldEdges = 0;    // undirected edges used by three or more triangles
  int inconsistentEdges = 0;   // edges used twice in the same direction (orientation flips)
  int degenerateTriangles = 0; // area ≤ degenerateArea, or a repeated vertex index
  int edgeCount = 0;           // undirected edges
  int components = 0;
  int eulerCharacteristic = 0; // V − E + F, V counting only referenced vertices
  bool closed() const { return boundaryEdges == 0; }
  bool edgeManifold() const { return nonManifoldEdges == 0; }
  bool consistentlyOriented() const { return inconsistentEdges == 0; }
  // Closed, edge-manifold, consistently oriented and without degenerate triangles.
  bool closedManifold() const { return closed() && edgeManifold() && consistentlyOriented() && degenerateTriangles == 0; }
};

// Topology and degeneracy checks. `degenerateArea`: triangles with area ≤ it count as degenerate
// (default: 1e-12 times the squared bounding-box diagonal). Without `countComponents`,
// `components` stays 0 (the piece count is a third of the check's time: docs/performance.md).
MeshCheck checkMesh(const TriMesh& mesh, double degenerateArea = -1, bool countComponents = true);

// Triangles whose unit normal makes an angle above 90° with the reference normals' mean at their
// corners (3 × V unit normals, e.g. vertexNormals or ∇f): a "flipped" triangle.
int countFlippedTriangles(const TriMesh& mesh, const Eigen::Matrix3Xd& referenceNormals);

// Area of triangle t.
inline double triangleArea(const TriMesh& mesh, int t) {
  const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t));
  return 0.5 * (mesh.vertices.col(mesh.triangles(1, t)) - a).cross(mesh.vertices.col(mesh.triangles(2, t)) - a).norm();
}

// Total area of the triangles.
double surfaceArea(const TriMesh& mesh);

// Signed volume enclosed by a closed mesh (positive when it is oriented outward).
double signedVolume(const TriMesh& mesh);
// The same of the closed piece made by `triangles` (ids into the mesh). Taken about the first
// one's first vertex (a closed piece's volume is the same about any point), so that a piece far
// smaller than its distance from the origin loses no digits to the offset.
double signedVolume(const TriMesh& mesh, const std::vector<int>& triangles);

// Undirected edge key of vertices a, b (order-free).
inline std::uint64_t edgeKey(int a, int b) {
  const std::uint32_t lo = static_cast<std::uint32_t>(a < b ? a : b), hi = static_cast<std::uint32_t>(a < b ? b : a);
  return (std::uint64_t(lo) << 32) | hi;
}

}  // namespace hermite
