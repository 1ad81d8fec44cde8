// Marching cubes with ambiguous faces decided by f (face_decider.h) and per-cube polygon chaining
// (marching_options.h), streamed through slabs of the grid (marching_slab.h) or, without culling,
// over the whole grid.

#include "core/mesh/marching_cubes.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/mesh/centre_vertices.h"
#include "core/mesh/cut_tips.h"
#include "core/mesh/face_decider.h"
#include "core/mesh/marching_anchors.h"
#include "core/mesh/marching_memory.h"
#include "core/mesh/marching_slab.h"
#include "core/mesh/near_mesh_distance.h"
#include "core/mesh/open_slivers.h"

namespace hermite {

namespace {

// Corner c of a cube is at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1) cells. A cube edge is named
// by its lower corner and axis: local id = 3 · corner + axis (24 slots, 12 used).
struct CubeTables {
  // Face f: its four corners counter-clockwise about the outward face normal.
  std::array<std::array<int, 4>, 6> faceCorners{};
  // Whether two local edges lie on a common face of the cube.
  std::array<std::array<bool, 24>, 24> shareFace{};

  CubeTables() {
    int f = 0;
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, w = (a + 2) % 3;  // e_u × e_w = e_a
      for (int side = 0; side < 2; ++side, ++f) {
        // (u, w) offsets counter-clockwise about +e_a; reversed for the face whose normal is −e_a.
        const int uw[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 4; ++i) {
          const int j = side ? i : (4 - i) % 4;
          faceCorners[f][i] = (side << a) | (uw[j][0] << u) | (uw[j][1] << w);
        }
        for (int i = 0; i < 4; ++i)
          for (int k = 0; k < 4; ++k)
            shareFace[faceEdge(f, i)][faceEdge(f, k)] = true;
      }
    }
  }
  // Local id of the edge from the face's corner i to corner i + 1.
  int faceEdge(int f, int i) const { return edgeBetween(faceCorners[f][i], faceCorners[f][(i + 1) % 4]); }
  static int edgeBetween(int c0, int c1) {
    const int diff = c0 ^ c1;
    const int axis = diff == 1 ? 0 : diff == 2 ? 1 : 2;
    return 3 * (c0 & c1) + axis;
  }
};

const CubeTables& tables() {
  static const CubeTables t;
  return t;
}

// Triangles of one layer of cubes: vertex ids ≥ 0 are edge vertices; −1 − i is the centre of
// centres[i] (the polygon's edge vertices).
struct LayerOutput {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::vector<int>> centres;
};

// Directed face segments of a cube with corner values v (insideMask: bit c set ⇔ v[c] < 0):
// next[e] = the edge the contour goes to from edge e (−1: none). On a face walked
// counter-clockwise about its outward normal, a crossing is A (inside → outside) or B
// (outside → inside); each segment runs from a B to an A, which orients the polygon so its fan
// triangles are counter-clockwise seen from outside (+∇f).
// `decided(f)` is face f's decision by f itself (face_decider.h): 1 or 0, or −1 for the
// asymptotic decider (face f = 2 · normal axis + side, as CubeTables numbers them).
template <class Decided>
std::array<int, 24> faceSegments(const std::array<double, 8>& v, int insideMask, const Decided& decided) {
  const CubeTables& T = tables();
  auto in = [&](int c) { return (insideMask >> c) & 1; };
  std::array<int, 24> next;
  next.fill(-1);
  for (int f = 0; f < 6; ++f) {
    const std::array<int, 4>& fc = T.faceCorners[f];
    int edges[4], isA[4], n = 0;
    for (int i = 0; i < 4; ++i)
      if (in(fc[i]) != in(fc[(i + 1) % 4])) {
        edges[n] = T.faceEdge(f, i);
        isA[n++] = in(fc[i]);
      }
    if (n == 2) {
      if (isA[0]) next[edges[1]] = edges[0];
      else next[edges[0]] = edges[1];
    } else if (n == 4) {
      // f at the bilinear interpolant's saddle, else the interpolant's own value there (the
      // asymptotic decider). The denominator is non-zero: the diagonal pairs have opposite signs.
      const int byF = decided(f);
      const double saddle = (v[fc[0]] * v[fc[2]] - v[fc[1]] * v[fc[3]]) / (v[fc[0]] + v[fc[2]] - v[fc[1]] - v[fc[3]]);
      const bool outsideConnected = byF >= 0 ? byF == 1 : saddle >= 0;  // then each inside corner is cut off alone
      for (int i = 0; i < 4; ++i) {
        const int j = (i + 1) % 4;
        if (outsideConnected && !isA[i]) next[edges[i]] = edges[j];  // B, then the A leaving the inside corner
        if (!outsideConnected && isA[i]) next[edges[j]] = edges[i];  // A, then the B leaving the outside corner
      }
    }
  }
  return next;
}

// The triangles of one contour polygon of the cube at `origin`: its n local edge ids in `loop`,
// in order. None when no vertex of it has data (the surface is open there); a fan whose
// diagonals never lie on a cube face, else a fan around a centre vertex.
void emitPolygon(const detail::MarchingGrid<3>& g, std::int64_t origin, const int* loop, int n, LayerOutput& out) {
  const CubeTables& T = tables();
  const auto cornerIndex = [&](int c) {
    return origin + (c & 1) * g.stride[0] + ((c >> 1) & 1) * g.stride[1] + ((c >> 2) & 1) * g.stride[2];
  };
  // A corner valid only through the field's extension beyond its data (validBatch's 2): every
  // vertex must have data, so the extension closes surfaces at the data's edge but grows none.
  bool extended = false;
  for (int c = 0; c < 8 && !g.valid.empty(); ++c) extended = extended || g.valid[static_cast<size_t>(cornerIndex(c))] == 2;
  int ids[12];
  int withData = 0;
  for (int i = 0; i < n; ++i) {
    ids[i] = g.vertexOn(cornerIndex(loop[i] / 3), loop[i] % 3);
    withData += g.isVertexValid(ids[i]);
  }
  if (extended ? withData < n : withData == 0) return;
  if (n == 3) {
    out.triangles.push_back({ids[0], ids[1], ids[2]});
    return;
  }
  int fanStart = -1;
  for (int s = 0; s < n && fanStart < 0; ++s) {
    bool ok = true;
    for (int j = 2; j <= n - 2 && ok; ++j) ok = !T.shareFace[loop[s]][loop[(s + j) % n]];
    if (ok) fanStart = s;
  }
  if (fanStart >= 0) {
    for (int j = 1; j <= n - 2; ++j)
      out.triangles.push_back({ids[fanStart], ids[(fanStart + j) % n], ids[(fanStart + j + 1) % n]});
  } else {
    const int centre = -1 - static_cast<int>(out.centres.size());
    out.centres.emplace_back(ids, ids + n);
    for (int i = 0; i < n; ++i) out.triangles.push_back({centre, ids[i], ids[(i + 1) % n]});
  }
}

void marchCube(const detail::MarchingGrid<3>& g, const detail::FaceDecisions& faces, std::int64_t origin,
               LayerOutput& out) {
  std::array<double, 8> v;
  int insideMask = 0;
  for (int c = 0; c < 8; ++c) {
    const std::int64_t idx = origin + (c & 1) * g.stride[0] + ((c >> 1) & 1) * g.stride[1] + ((c >> 2) & 1) * g.stride[2];
    if (!g.isValid(idx)) return;  // no data at a corner: no geometry in the cube
    v[c] = g.values[idx];
    if (v[c] < 0) insideMask |= 1 << c;
  }
  if (insideMask == 0 || insideMask == 255) return;
  const auto decided = [&](int f) {
    const int a = f / 2, side = f % 2;
    return faces.lookup(3 * (origin + side * g.stride[a]) + a);
  };
  const std::array<int, 24> next = faceSegments(v, insideMask, decided);
  std::array<bool, 24> seen{};
  for (int start = 0; start < 24; ++start) {
    if (next[start] < 0 || seen[start]) continue;
    int loop[12], n = 0;
    for (int e = start; !seen[e] && n < 12; e = next[e]) {
      seen[e] = true;
      loop[n++] = e;
    }
    emitPolygon(g, origin, loop, n, out);
  }
}



// Starts for the centre vertices (centre_vertices.h): per polygon its mean vertex, area normal and
// the box of its vertices.
struct CentreStarts {
  Points<3> X, axis, lo, hi;
};

CentreStarts centreStarts(const Points<3>& vertices, const std::vector<LayerOutput>& out, size_t count) {
  CentreStarts s;
  for (Points<3>* m : {&s.X, &s.axis, &s.lo, &s.hi}) m->resize(3, static_cast<Eigen::Index>(count));
  Eigen::Index c = 0;
  for (const LayerOutput& o : out)
    for (const std::vector<int>& ring : o.centres) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero(), area = Eigen::Vector3d::Zero();
      Eigen::Vector3d lo = vertices.col(ring[0]), hi = lo;
      for (int id : ring) {
        mean += vertices.col(id);
        lo = lo.cwiseMin(vertices.col(id));
        hi = hi.cwiseMax(vertices.col(id));
      }
      mean /= static_cast<double>(ring.size());
      for (size_t i = 0; i < ring.size(); ++i)
        area += (vertices.col(ring[i]) - mean).cross(vertices.col(ring[(i + 1) % ring.size()]) - mean);
      s.X.col(c) = mean;
      s.axis.col(c) = area;
      s.lo.col(c) = lo;
      s.hi.col(c) = hi;
      ++c;
    }
  return s;
}

// The mesh from the edge vertices (3 × V positions and ∇f), the cubes' triangles and their
// centre vertices, in the order of `out`: centres follow the edge vertices, placed on f = 0 by
// placeCentreVertices; normals are ∇f / ‖∇f‖, the area-weighted mesh normal where ∇f vanishes.
// Where the field has no data somewhere (`someInvalid`), edge vertices no triangle uses are
// dropped. `report` gains the centres' count and |f|.
TriMesh assembleMesh(const ImplicitField<3>& field, const Points<3>& vertices, const Points<3>& gradients,
                     const std::vector<LayerOutput>& out, bool someInvalid, const CancelToken* cancel,
                     MarchingReport* report) {
  const int V = static_cast<int>(vertices.cols());
  size_t nCentres = 0, nTriangles = 0;
  for (const LayerOutput& o : out) {
    nCentres += o.centres.size();
    nTriangles += o.triangles.size();
  }
  TriMesh mesh;
  mesh.vertices.resize(3, V + static_cast<Eigen::Index>(nCentres));
  mesh.vertices.leftCols(V) = vertices;
  mesh.normals.resize(3, mesh.vertexCount());
  mesh.normals.leftCols(V) = gradients;
  if (nCentres > 0) {
    CentreStarts s = centreStarts(vertices, out, nCentres);
    Points<3> G;
    const CentreVertexReport placed = placeCentreVertices(field, s.X, s.axis, s.lo, s.hi, G, cancel);
    mesh.vertices.rightCols(static_cast<Eigen::Index>(nCentres)) = s.X;
    mesh.normals.rightCols(static_cast<Eigen::Index>(nCentres)) = G;
    if (report) {
      report->centreVertices = placed.centres;
      report->centresOffZeroSet = placed.offZeroSet;
      report->maxAbsF = std::max(report->maxAbsF, placed.maxAbsF);
    }
  }
  mesh.triangles.resize(3, static_cast<Eigen::Index>(nTriangles));
  int centreBase = V;
  Eigen::Index t = 0;
  for (const LayerOutput& o : out) {
    for (const std::array<int, 3>& tri : o.triangles) {
      for (int k = 0; k < 3; ++k) mesh.triangles(k, t) = tri[k] >= 0 ? tri[k] : centreBase - 1 - tri[k];
      ++t;
    }
    centreBase += static_cast<int>(o.centres.size());
  }
  const Eigen::Matrix3Xd fallback = vertexNormals(mesh);
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const double len = mesh.normals.col(v).norm();
    if (len > 1e-300 && std::isfinite(len)) mesh.normals.col(v) /= len;
    else mesh.normals.col(v) = fallback.col(v);
  }
  if (someInvalid) dropUnusedVertices(mesh);
  return mesh;
}

// The whole grid at once (MarchingOptions::cull off): f at every point, every cell marched.
TriMesh marchDense(const ImplicitField<3>& field, const GridLines<3>& lines, const Vec<3>& h,
                   const MarchingOptions& options, MarchingReport* report, detail::AnchorCells* anchors) {
  detail::MarchingGrid<3> g = detail::sampleGrid<3>(field, lines, h, options, report);
  const detail::CullBlock<3> whole{{0, 0, 0}, std::max({g.n[0], g.n[1], g.n[2]})};
  const std::vector<std::int64_t> cells = detail::signChangingCells(g, {whole});
  if (anchors) detail::markSeenAnchors(*anchors, g, cells);
  detail::placeEdgeVertices<3>(g, field, options, report);
  const detail::FaceDecisions faces = detail::decideAmbiguousFaces(g, field, cells, options.cancel);
  const int layers = g.n[2];
  std::vector<LayerOutput> out(static_cast<size_t>(layers));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        marchCube(g, faces, i + g.stride[1] * j + g.stride[2] * k, out[static_cast<size_t>(k)]);
  return assembleMesh(field, g.vertices, g.gradients, out, !g.valid.empty(), options.cancel, report);
}

// The cubes of the sorted cells, in chunks marched in parallel and kept in order.
std::vector<LayerOutput> marchCells(const detail::MarchingGrid<3>& g, const detail::FaceDecisions& faces,
                                    const std::vector<std::int64_t>& cells) {
  constexpr std::size_t kChunk = 2048;
  const std::int64_t chunks = static_cast<std::int64_t>((cells.size() + kChunk - 1) / kChunk);
  std::vector<LayerOutput> out(static_cast<size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::size_t end = std::min(cells.size(), (static_cast<std::size_t>(c) + 1) * kChunk);
    for (std::size_t i = static_cast<std::size_t>(c) * kChunk; i < end; ++i)
      marchCube(g, faces, cells[i], out[static_cast<size_t>(c)]);
  }
  return out;
}

// A slab's triangles while their vertex ids are still local (indices into its edgeKeys): the
// edges on its top point layer belong to the next slab, which numbers them.
struct PendingSlab {
  std::vector<LayerOutput> out;
  std::vector<std::int64_t> edgeKeys;
  std::int64_t owned = 0;     // its own edges: those below its top point layer, first in edgeKeys
  std::int64_t base = 0;      // global id of its first own vertex
  std::int64_t keyShift = 0;  // a top-layer edge's key here minus its key in the next slab
};

// Moves the slab's triangles to `done` with global vertex ids; `nextKeys` and `nextBase` are
// the next slab's edge keys and first id (unused when every edge is the slab's own).
void resolveSlab(PendingSlab& s, const std::vector<std::int64_t>& nextKeys, std::int64_t nextBase,
                 std::vector<LayerOutput>& done) {
  auto global = [&](int v) {
    if (v < s.owned) return static_cast<int>(s.base + v);
    const std::int64_t key = s.edgeKeys[static_cast<size_t>(v)] - s.keyShift;
    const auto it = std::lower_bound(nextKeys.begin(), nextKeys.end(), key);
    if (it == nextKeys.end() || *it != key) throw std::logic_error("marching: slab seams disagree");
    return static_cast<int>(nextBase + (it - nextKeys.begin()));
  };
  for (LayerOutput& o : s.out) {
    for (std::array<int, 3>& tri : o.triangles)
      for (int& v : tri)
        if (v >= 0) v = global(v);
    for (std::vector<int>& c : o.centres)
      for (int& v : c) v = global(v);
    done.push_back(std::move(o));
  }
  s.out.clear();
}

// Everything one slab contributes, added to the running mesh: its own vertices (positions and
// ∇f) and, once the next slab numbers the shared top-layer edges, its triangles.
struct StreamState {
  std::vector<double> positions, gradients;  // 3 per vertex
  std::vector<LayerOutput> done;
  PendingSlab pending;
  bool havePending = false;
  std::int64_t evaluated = 0;
  double evaluateMs = 0, maxAbsF = 0;
};

void streamSlab(const ImplicitField<3>& field, const GridLines<3>& lines, const Vec<3>& h, int slab,
                const MarchingOptions& options, StreamState& st, detail::AnchorCells* anchors) {
  const std::array<int, 3> n = gridCells<3>(lines);
  const int slabs = (n[2] + detail::kSlabCells - 1) / detail::kSlabCells;
  const int k0 = slab * detail::kSlabCells, layers = std::min(detail::kSlabCells, n[2] - k0);
  const bool last = slab == slabs - 1;
  const auto t0 = std::chrono::steady_clock::now();
  detail::MarchingGrid<3> g = detail::slabGrid(lines, h, k0, layers);
  const std::vector<detail::CullBlock<3>> blocks = detail::undecidedBlocks(g, field, options.cancel);
  std::function<void(double)> progress;
  if (options.progress) progress = [&](double f) { options.progress((slab + f) / slabs); };
  st.evaluated += detail::evaluateSlab(g, field, blocks, options.cancel, progress);
  st.evaluateMs += msSince(t0);
  const std::vector<std::int64_t> cells = detail::signChangingCells(g, blocks);
  if (anchors) detail::markSeenAnchors(*anchors, g, cells);
  if (!field.everywhereValid()) detail::slabValidity(g, field, cells, options.cancel);
  detail::slabEdges(g, cells);
  if (st.havePending) resolveSlab(st.pending, g.edgeKeys, st.pending.base + st.pending.owned, st.done);
  st.maxAbsF = std::max(st.maxAbsF, detail::refineEdgeVertices<3>(g, field, options));
  detail::markVertexValidity<3>(g, field, options.cancel);
  // The top point layer's edges are the next slab's (keys from point layer `layers` on).
  const std::int64_t topKey = 3 * g.stride[2] * layers;
  const std::int64_t owned =
      last ? static_cast<std::int64_t>(g.edgeKeys.size())
           : std::lower_bound(g.edgeKeys.begin(), g.edgeKeys.end(), topKey) - g.edgeKeys.begin();
  st.positions.insert(st.positions.end(), g.vertices.data(), g.vertices.data() + 3 * owned);
  st.gradients.insert(st.gradients.end(), g.gradients.data(), g.gradients.data() + 3 * owned);
  const std::int64_t base = st.havePending ? st.pending.base + st.pending.owned : 0;
  const detail::FaceDecisions faces = detail::decideAmbiguousFaces(g, field, cells, options.cancel);
  st.pending = PendingSlab{marchCells(g, faces, cells), std::move(g.edgeKeys), owned, base, topKey};
  st.havePending = true;
}

// The grid in slabs of detail::kSlabCells cell layers (marching_slab.h): memory O(cross-section).
TriMesh marchStreamed(const ImplicitField<3>& field, const GridLines<3>& lines, const Vec<3>& h,
                      const MarchingOptions& options, MarchingReport* report, detail::AnchorCells* anchors) {
  const std::array<int, 3> n = gridCells<3>(lines);
  checkMemory(marchingSlabPlan(n, options.resolution), kMarchingRemedy);
  const int slabs = (n[2] + detail::kSlabCells - 1) / detail::kSlabCells;
  StreamState st;
  for (int s = 0; s < slabs; ++s) {
    throwIfCancelled(options.cancel);
    streamSlab(field, lines, h, s, options, st, anchors);
  }
  resolveSlab(st.pending, {}, 0, st.done);
  if (options.progress) options.progress(1.0);
  const Eigen::Index V = static_cast<Eigen::Index>(st.positions.size() / 3);
  const Points<3> vertices = Eigen::Map<const Points<3>>(st.positions.data(), 3, V);
  const Points<3> gradients = Eigen::Map<const Points<3>>(st.gradients.data(), 3, V);
  if (report) {
    report->cells = {n[0], n[1], n[2]};
    report->gridPoints = (std::int64_t(n[0]) + 1) * (n[1] + 1) * (n[2] + 1);
    report->evaluatedPoints = st.evaluated;
    report->evaluateMs = st.evaluateMs;
    report->maxAbsF = st.maxAbsF;
  }
  return assembleMesh(field, vertices, gradients, st.done, !field.everywhereValid(), options.cancel, report);
}

// One contouring pass over `lines`, recording which anchors it sees when `anchors` is given.
TriMesh marchOnce(const ImplicitField<3>& field, const GridLines<3>& lines, const Vec<3>& h,
                  const MarchingOptions& options, MarchingReport* report, detail::AnchorCells* anchors) {
  return options.cull ? marchStreamed(field, lines, h, options, report, anchors)
                      : marchDense(field, lines, h, options, report, anchors);
}

// The lines with the intervals near the missed anchors' cells split (MarchingOptions::anchors),
// or none when even halving them (with `halving`; otherwise cutting them in kAnchorSplit) would
// more than double an axis's cells, or the refined grid (its slabs when streamed) would need more
// than half the available memory.
std::optional<GridLines<3>> refinedLines(const GridLines<3>& lines, const std::vector<std::array<int, 3>>& missed,
                                         const MarchingOptions& options, bool halving) {
  const std::array<std::vector<char>, 3> near = intervalsNear<3>(lines, missed, kAnchorReach);
  const std::array<int, 3> n = gridCells<3>(lines);
  for (const int factor : {kAnchorSplit, halving ? 2 : kAnchorSplit}) {
    std::array<int, 3> m{};
    bool fits = true;
    for (int a = 0; a < 3; ++a) {
      const auto marked = std::count(near[a].begin(), near[a].end(), char(1));
      m[a] = n[a] + static_cast<int>(marked) * (factor - 1);
      fits = fits && m[a] <= 2 * n[a];
    }
    if (!fits) continue;
    const PlannedAllocation plan =
        options.cull ? marchingSlabPlan(m, options.resolution) : marchingGridPlan<3>(m, options.resolution);
    if (plan.bytes > availableMemory().bytes / 2) return std::nullopt;
    return splitGridIntervals<3>(lines, near, factor);
  }
  return std::nullopt;
}

// The pass over refined lines. The report keeps the uniform grid's cells, adds this pass's
// evaluations and says how many anchors it still misses; `stillMissed` receives them.
TriMesh contourRefined(const ImplicitField<3>& field, const ImplicitField<3>& contoured, const GridLines<3>& lines,
                       const Vec<3>& h, const MarchingOptions& options, MarchingReport* report,
                       std::vector<int>* stillMissed) {
  detail::AnchorCells seen = detail::locateAnchors(lines, *options.anchors);
  MarchingReport pass;
  TriMesh mesh = marchOnce(contoured, lines, h, options, &pass, &seen);
  if (report) {
    report->evaluateMs += pass.evaluateMs;
    report->evaluatedPoints += pass.evaluatedPoints;
    report->maxAbsF = pass.maxAbsF;
    report->centreVertices = pass.centreVertices;
    report->centresOffZeroSet = pass.centresOffZeroSet;
    report->refinedCells = pass.cells;
  }
  *stillMissed = detail::missedAnchors(seen, *options.anchors, field, h.norm());
  if (report) report->stillMissed = static_cast<int>(stillMissed->size());
  return mesh;
}

double minGridStep(const GridLines<3>& lines) {
  double step = std::numeric_limits<double>::infinity();
  for (const std::vector<double>& l : lines)
    for (size_t i = 0; i + 1 < l.size(); ++i) step = std::min(step, l[i + 1] - l[i]);
  return step;
}

// The columns `which` of P.
Points<3> columnsOf(const Points<3>& P, const std::vector<int>& which) {
  Points<3> out(3, static_cast<Eigen::Index>(which.size()));
  for (size_t i = 0; i < which.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = P.col(which[i]);
  return out;
}

// How far each of `points` lies from `mesh`, in cell diagonals d, up to 1.
std::vector<double> offMesh(const TriMesh& mesh, const Points<3>& points, double d) {
  std::vector<double> out = distancesToMeshWithin(mesh, points, d);
  for (double& x : out) x /= d;
  return out;
}

// Whether so many missed anchors lie more than half a cell diagonal off the mesh that a thin
// part is contoured away from its samples (kRefineOffShare).
bool offItsSamples(const TriMesh& mesh, const Points<3>& missed, Eigen::Index anchors, double d) {
  const std::vector<double> off = offMesh(mesh, missed, d);
  const auto far = std::count_if(off.begin(), off.end(), [](double x) { return x > 0.5; });
  return static_cast<double>(far) >= kRefineOffShare * static_cast<double>(anchors);
}

// Whether `finer` lies nearer the anchors either grid missed than `mesh` does: the sum of their
// distances (in cell diagonals, each capped at 1) is at most half of mesh's.
bool nearerItsSamples(const TriMesh& mesh, const TriMesh& finer, const Points<3>& anchors, std::vector<int> missed,
                      double d) {
  std::sort(missed.begin(), missed.end());
  missed.erase(std::unique(missed.begin(), missed.end()), missed.end());
  const Points<3> at = columnsOf(anchors, missed);
  const std::vector<double> a = offMesh(mesh, at, d), b = offMesh(finer, at, d);
  return 2 * std::accumulate(b.begin(), b.end(), 0.0) <= std::accumulate(a.begin(), a.end(), 0.0);
}

// The anchors the refined pass cuts the cells of: those the uniform grid `missed` and, when they
// are at least kRefineOffShare of all, those on the pockets among the pieces `cut` leaves out
// (samplesOnPockets; `pocketed` says so): a pocket leaves the mesh with its samples, and a finer
// grid can open the gap's mouth and join its walls to the surface.
std::vector<int> anchorsToRefine(const TriMesh& mesh, const TipCandidates& tips, const std::vector<char>& cut,
                                 std::vector<int> missed, const Points<3>& anchors, double d, bool* pocketed) {
  const std::vector<int> onPockets = samplesOnPockets(mesh, tips, cut, d, anchors);
  *pocketed = static_cast<double>(onPockets.size()) >= kRefineOffShare * static_cast<double>(anchors.cols());
  if (*pocketed) missed.insert(missed.end(), onPockets.begin(), onPockets.end());
  return missed;
}

// The mesh again on refined lines when the uniform pass missed anchors and came out in pieces
// that are not all cut-off tips, or lies off many of them (MarchingOptions::anchors), `usedLines`
// receiving them; otherwise `mesh` as it is, the report saying why. `stillMissed` receives the
// anchors the uniform grid misses and, when the refined mesh is returned, those it misses too
// (some twice).
TriMesh refineForAnchors(const ImplicitField<3>& field, const ImplicitField<3>& contoured, const GridLines<3>& lines,
                         const Vec<3>& h, const detail::AnchorCells& seen, TriMesh mesh, const MarchingOptions& options,
                         MarchingReport* report, std::optional<GridLines<3>>* usedLines, std::vector<int>* stillMissed) {
  using Refinement = MarchingReport::Refinement;
  *stillMissed = detail::missedAnchors(seen, *options.anchors, field, h.norm());
  const Points<3>& anchors = *options.anchors;
  const Points<3> missedAt = columnsOf(anchors, *stillMissed);
  // The uniform mesh's pieces, and those that are tips the grid cut off a thin part or pockets it
  // kept of a thin gap (cut_tips.h): left out after this anyway.
  const TipCandidates tips = tipCandidates(mesh, h.norm());
  const int before = tips.count;
  const std::vector<char> cut = cutTipsToDrop(mesh, tips, missedAt, h.norm(), &anchors);
  bool pocketed = false;
  const std::vector<std::array<int, 3>> missed =
      detail::anchorCellsOf(seen, anchorsToRefine(mesh, tips, cut, *stillMissed, anchors, h.norm(), &pocketed));
  if (missed.empty()) return mesh;
  MarchingReport local;
  MarchingReport& r = report ? *report : local;
  r.missedAnchors = r.stillMissed = static_cast<int>(missed.size());
  r.refinement = Refinement::OnePiece;
  // A thin part the grid steps over splits the surface, or stays joined by a ribbon a cell wide
  // that lies off its samples; a thin rim it truncates (the edge of an ear) leaves one piece with
  // few samples far off it and is not worth a second pass. A ribbon is resolved only by cutting
  // its cells in kAnchorSplit: thin parts so spread that only halving fits (sheets across a whole
  // model, CGAL's boeing) would be contoured again at twice the resolution and no nearer.
  // Pieces beyond the first that are all such tips or pockets do not call for it: a second pass
  // would cost a whole contour for them, and on the Stanford dragon's fins and cracks did not join
  // or fill them (docs/maths.md, Contouring: cut-off tips) — unless many samples lie on a pocket.
  const bool off = offItsSamples(mesh, missedAt, anchors.cols(), h.norm());
  const bool pieces = pocketed || before - std::count(cut.begin(), cut.end(), char(1)) > 1;
  if (!pieces && !off) return mesh;
  r.refinement = Refinement::TooLarge;
  std::optional<GridLines<3>> refined = refinedLines(lines, missed, options, pieces);
  if (!refined) return mesh;
  MarchingReport pass = r;
  std::vector<int> finerMissed;
  TriMesh finer = contourRefined(field, contoured, *refined, h, options, &pass, &finerMissed);
  if (options.review) options.review(finer, *refined);
  // Fewer pieces, or as many and nearer the missed samples, or none of it: more pieces on a finer
  // grid are the field's own (a fit that breaks up), not steps the grid took over a thin part.
  r.refinement = Refinement::NoGain;
  r.evaluateMs = pass.evaluateMs;
  r.evaluatedPoints = pass.evaluatedPoints;
  const int after = vertexConnectedComponentCount(finer);
  if (after > before) return mesh;
  std::vector<int> both = *stillMissed;
  both.insert(both.end(), finerMissed.begin(), finerMissed.end());
  if (after == before && !(off && nearerItsSamples(mesh, finer, anchors, both, h.norm()))) {
    if (off) r.refinement = Refinement::NotNearer;
    return mesh;
  }
  pass.refinement = Refinement::Refined;
  pass.minStep = minGridStep(*refined);
  r = pass;
  *usedLines = std::move(refined);
  // Either grid's missed anchors mark a thin part: a tip the finer grid still cuts off lies
  // beside the coarse grid's (cut_tips.h).
  *stillMissed = std::move(both);
  return finer;
}

}  // namespace

TriMesh marchingCubes(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options,
                      MarchingReport* report, GridLines<3>* usedLines) {
  const auto t0 = std::chrono::steady_clock::now();
  const Vec<3> h = detail::marchingCellSize<3>(box, options.resolution);
  const std::unique_ptr<ImplicitField<3>> near = field.forGridCells(h.norm());
  const ImplicitField<3>& f = near ? *near : field;
  const GridLines<3> lines = detail::marchingLines<3>(box, options.resolution);
  std::optional<detail::AnchorCells> seen;
  if (options.anchors && options.anchors->cols() > 0) seen = detail::locateAnchors(lines, *options.anchors);
  TriMesh mesh = marchOnce(f, lines, h, options, report, seen ? &*seen : nullptr);
  if (options.review) options.review(mesh, lines);
  if (report) report->minStep = minGridStep(lines);
  std::optional<GridLines<3>> refined;
  std::vector<int> missed;
  if (seen) mesh = refineForAnchors(field, f, lines, h, *seen, std::move(mesh), options, report, &refined, &missed);
  if (usedLines) *usedLines = refined ? std::move(*refined) : lines;
  // Tips of thin parts and pockets of thin gaps the grid cut off, beside samples it misses
  // (cut_tips.h).
  int gaps = 0;
  const int cut = seen ? dropCutTips(mesh, columnsOf(*options.anchors, missed), h.norm(), &gaps, options.anchors) : 0;
  if (report) report->droppedTips = cut - gaps;
  if (report) report->droppedGaps = gaps;
  // Pieces cut open where the field has no data that are smaller than a cell face (open_slivers.h).
  const int slivers = dropGridSlivers(mesh, field, h);
  if (report) report->droppedSlivers = slivers;
  if (report) report->totalMs = msSince(t0);
  return mesh;
}

TriMesh marchingCubesPass(const ImplicitField<3>& field, const GridLines<3>& lines, const Vec<3>& h,
                          const MarchingOptions& options) {
  const std::unique_ptr<ImplicitField<3>> near = field.forGridCells(h.norm());
  return marchOnce(near ? *near : field, lines, h, options, nullptr, nullptr);
}

}  // namespace hermite
