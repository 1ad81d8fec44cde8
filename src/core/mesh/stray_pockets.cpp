#include "core/mesh/stray_pockets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/mesh/contour_patch.h"
#include "core/mesh/cut_tips.h"
#include "core/mesh/marching_grid.h"
#include "core/mesh/occupied_cells.h"
#include "core/mesh/winding_guard_field.h"
#include "core/points/uniform_winding.h"

namespace hermite {

namespace {

// The occupancy cells are half the contour grid's, and never wider than this share of the
// sample spacing √(A / N) (A the contour's area): at 256³ for 200 000 samples the half cell is
// up to 1.27 of it on CGAL's models and the dragon (the dino; femur, long and thin, 1.68); on a
// grid coarse for its samples (the dragon's million at 256³: 2.24) the cells follow the samples
// instead, so that "far" keeps meaning a few spacings.
constexpr double kOccupancySpacing = 1.3;
constexpr int kPieceProbes = 64;         // vertices of a piece whose winding number is averaged
// A vertex with no sample within kNearFar spacings whose samples within kPlaneReach spacings
// put it kPlaneFar spacings off their tangent planes on average is far too (offTheirPlanes;
// how many pass each test: docs/maths.md, Stray pockets).
constexpr double kNearFar = 1.0;
constexpr double kPlaneReach = 2.5;
constexpr double kPlaneFar = 0.5;
// With no sample within kAloneFar spacings a vertex is far whatever the planes: beyond the tip of
// a part thinner than the sampling the samples of its two sides put it on average near their
// planes. A vertex of a uniformly sampled surface is that far from every sample with probability
// about e^(−π·1.5²) ≈ 0.001, and its winding number is about ½ there, so it is no stray.
constexpr double kAloneFar = 1.5;
// Up to this many far vertices the rough winding number (every sample standing for A / N) filters
// them before the samples' winding number is built: the sums cost well under half of that build
// (docs/performance.md, "Stray review").
constexpr std::size_t kRoughWindingLimit = 1024;
// Pieces with more than this share of the mesh's triangles stay whatever their winding number: a
// stray pocket is small, and a large piece off ½ means samples whose normals disagree (an
// inconsistently oriented or self-intersecting source), not a pocket.
constexpr double kPieceShare = 0.05;
// A guard round contours again only the cells about the new strays while they are at most this
// share of the grid's; beyond it, the whole grid (contour_patch.h).
constexpr double kMaxPatchShare = 0.25;

bool overlap(const Box<3>& a, const Box<3>& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

// 1 for the vertices of the mesh's largest piece, else 0.
std::vector<char> largestPieceVertices(const TriMesh& mesh) {
  const MeshPieces pieces(mesh);
  std::vector<char> on(static_cast<std::size_t>(mesh.vertexCount()), 0);
  for (int t = 0; t < mesh.triangleCount(); ++t)
    if (pieces.of[static_cast<std::size_t>(t)] == pieces.largest)
      for (int k = 0; k < 3; ++k) on[static_cast<std::size_t>(mesh.triangles(k, t))] = 1;
  return on;
}

// Keeps the entries of `which` whose winding number w (one per entry, in order) is decided.
void keepWhereDecided(std::vector<Eigen::Index>& which, const std::vector<double>& w) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < which.size(); ++i)
    if (windingDecided(w[i])) which[kept++] = which[i];
  which.resize(kept);
}

// Whether x, with no sample within kNearFar spacings, has none within kAloneFar either or lies on
// average kPlaneFar spacings or more off the tangent planes of the samples within kPlaneReach
// spacings: a surface that strayed between the samples (a cap past the tip of a thin fin, a dent
// into the solid), not one passing between them, which stays within a fraction of a spacing of
// their planes. Or, on average outside the planes, kPlaneFar or more outside one of them: beside
// a convex edge the other face's samples put a bulge behind their planes, and the mean hides it
// (docs/maths.md, Stray pockets). Not the mirror inside: behind one plane is where the internal
// sheets of a self-intersecting surface put their vertices.
bool offTheirPlanes(const HermiteSamples<3>& samples, const OccupiedCells& bySpacing, double spacing, const Vec<3>& x,
                    std::vector<int>& near) {
  bySpacing.samplesWithin(x, kNearFar * spacing, near, 1);
  if (!near.empty()) return false;
  bySpacing.samplesWithin(x, kPlaneReach * spacing, near);
  if (near.empty()) return false;  // no plane to measure against: left to the occupancy test
  double sum = 0, most = -std::numeric_limits<double>::infinity(), nearest2 = std::numeric_limits<double>::infinity();
  for (int i : near) {
    const double offset = samples.normals.col(i).dot(x - samples.points.col(i));
    sum += offset;
    most = std::max(most, offset);
    nearest2 = std::min(nearest2, (x - samples.points.col(i)).squaredNorm());
  }
  const double meanOffset = std::abs(sum / static_cast<double>(near.size()));
  const bool outsideOne = sum > 0 && most >= kPlaneFar * spacing;
  return nearest2 >= kAloneFar * kAloneFar * spacing * spacing || meanOffset >= kPlaneFar * spacing || outsideOne;
}

// The columns of X that are off their samples' planes (offTheirPlanes, in parallel).
std::vector<Eigen::Index> offPlaneVertices(const Points<3>& X, const HermiteSamples<3>& samples,
                                           const OccupiedCells& bySpacing, double spacing) {
  const Eigen::Index n = X.cols();
  std::vector<char> off(static_cast<std::size_t>(n), 0);
#pragma omp parallel
  {
    std::vector<int> near;
#pragma omp for schedule(static)
    for (Eigen::Index v = 0; v < n; ++v)
      off[static_cast<std::size_t>(v)] = offTheirPlanes(samples, bySpacing, spacing, X.col(v), near);
  }
  std::vector<Eigen::Index> out;
  for (Eigen::Index v = 0; v < n; ++v)
    if (off[static_cast<std::size_t>(v)]) out.push_back(v);
  return out;
}

// Keeps the entries of `which` (columns of X) where the samples' winding number is decided,
// `windingOf()` giving it. Up to kRoughWindingLimit of them are first filtered by the rough winding
// number (uniform_winding.h: every sample standing for A / N), so that a few far vertices where
// that is not decided never build it.
template <class WindingOf>
void keepDecided(const HermiteSamples<3>& samples, double spacing, const Points<3>& X,
                 std::vector<Eigen::Index>& which, WindingOf&& windingOf) {
  if (which.size() <= kRoughWindingLimit) keepWhereDecided(which, uniformAreaWinding(samples, spacing, X, which));
  if (which.empty()) return;
  keepWhereDecided(which, windingOf().at(Points<3>(X(Eigen::all, which))));
}

// The vertices of the mesh's largest piece far from the samples whose winding number is decided:
// a pocket joined to the surface (a piece of its own is the piece rule's). Far means the
// occupancy's test, or off the samples' planes (offPlaneVertices; `bySpacing` holds the samples
// in cells of one spacing). `windingOf()` gives the winding number; it is called only when some
// far vertex passes the rough filter (keepDecided; a clean contour never builds it).
template <class WindingOf>
std::vector<Vec<3>> strayVertices(const TriMesh& mesh, const HermiteSamples<3>& samples, const OccupiedCells& occupied,
                                  const OccupiedCells& bySpacing, double spacing, WindingOf&& windingOf) {
  std::vector<Eigen::Index> far = offPlaneVertices(mesh.vertices, samples, bySpacing, spacing);
  const Eigen::Index n = mesh.vertices.cols();
  std::vector<char> alone(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(static)
  for (Eigen::Index v = 0; v < n; ++v)
    alone[static_cast<std::size_t>(v)] = occupied.farFromSamples(mesh.vertices.col(v));
  for (Eigen::Index v = 0; v < n; ++v)
    if (alone[static_cast<std::size_t>(v)]) far.push_back(v);
  if (far.empty()) return {};
  std::sort(far.begin(), far.end());
  far.erase(std::unique(far.begin(), far.end()), far.end());
  const std::vector<char> main = largestPieceVertices(mesh);
  far.erase(std::remove_if(far.begin(), far.end(), [&](Eigen::Index v) { return !main[static_cast<std::size_t>(v)]; }),
            far.end());
  keepDecided(samples, spacing, mesh.vertices, far, windingOf);
  std::vector<Vec<3>> strays;
  for (Eigen::Index v : far) strays.push_back(mesh.vertices.col(v));
  return strays;
}

// Per piece (`piece`: one per triangle) where `wanted`, the mean winding number of up to
// kPieceProbes of its vertices; 0 elsewhere.
std::vector<double> meanWindings(const TriMesh& mesh, const std::vector<int>& piece, const std::vector<char>& wanted,
                                 const CloudWinding<3>& winding) {
  std::vector<std::vector<int>> probes(wanted.size());
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const std::size_t c = static_cast<std::size_t>(piece[static_cast<std::size_t>(t)]);
    if (wanted[c] && static_cast<int>(probes[c].size()) < kPieceProbes) probes[c].push_back(mesh.triangles(0, t));
  }
  std::vector<double> mean(wanted.size(), 0.0);
  for (std::size_t c = 0; c < wanted.size(); ++c) {
    if (probes[c].empty()) continue;
    for (int v : probes[c]) mean[c] += winding.at(Vec<3>(mesh.vertices.col(v)));
    mean[c] /= static_cast<double>(probes[c].size());
  }
  return mean;
}

// Leaves out the components other than the largest, of at most kPieceShare of the triangles,
// whose vertices' mean winding number (over up to kPieceProbes of them) is above kPieceInside
// or below kPieceOutside. Returns their bounding boxes. `windingOf()` gives the winding
// number; it is called only when there is such a small piece (a mesh of two large true pieces
// never builds it).
template <class WindingOf>
std::vector<Box<3>> dropStrayPieces(TriMesh& mesh, WindingOf&& windingOf) {
  const MeshPieces pieces(mesh);
  const auto small = [&](int c) {
    return c != pieces.largest && pieces.size[static_cast<std::size_t>(c)] <= kPieceShare * mesh.triangleCount();
  };
  bool any = false;
  for (int c = 0; c < pieces.count() && !any; ++c) any = small(c);
  if (!any) return {};
  const std::vector<int>& comp = pieces.of;
  std::vector<char> drop(static_cast<std::size_t>(pieces.count()), 0);
  for (int c = 0; c < pieces.count(); ++c) drop[static_cast<std::size_t>(c)] = small(c);
  const std::vector<double> mean = meanWindings(mesh, comp, drop, windingOf());
  for (int c = 0; c < pieces.count(); ++c)
    drop[static_cast<std::size_t>(c)] = drop[static_cast<std::size_t>(c)] &&
                                        (mean[static_cast<std::size_t>(c)] > kPieceInside ||
                                         mean[static_cast<std::size_t>(c)] < kPieceOutside);
  const std::vector<Box<3>> boxes = componentBoxes(mesh, comp, pieces.count());
  dropComponents(mesh, comp, drop);
  std::vector<Box<3>> out;
  for (int c = 0; c < pieces.count(); ++c)
    if (drop[static_cast<std::size_t>(c)]) out.push_back(boxes[static_cast<std::size_t>(c)]);
  return out;
}

// Leaves out the pieces that could be tips the grid cut off a thin part (cut_tips.h; not the
// pockets of a gap, whose winding number is above ½) whose mean winding number is at least
// kPieceOutside (else dropStrayPieces did) and below kTipWinding.
// Returns how many. `windingOf()` gives the winding number; it is called only when there are
// candidates.
template <class WindingOf>
int dropWindingTips(TriMesh& mesh, WindingOf&& windingOf, double cellDiagonal) {
  const TipCandidates c = tipCandidates(mesh, cellDiagonal);
  std::vector<char> drop(static_cast<std::size_t>(c.count), 0);
  for (std::size_t k = 0; k < c.pieces.size(); ++k) drop[static_cast<std::size_t>(c.pieces[k])] = !c.gap[k];
  if (std::find(drop.begin(), drop.end(), 1) == drop.end()) return 0;
  const std::vector<double> mean = meanWindings(mesh, c.piece, drop, windingOf());
  for (std::size_t k = 0; k < c.pieces.size(); ++k) {
    const std::size_t p = static_cast<std::size_t>(c.pieces[k]);
    drop[p] = !c.gap[k] && mean[p] >= kPieceOutside && mean[p] < kTipWinding;
  }
  return dropComponents(mesh, c.piece, drop);
}

// The contours of one field and its guarded versions, sharing the samples' occupancy, their
// winding number (built on first use) and the guard region.
class StrayContour {
 public:
  StrayContour(const HermiteSamples<3>& samples, const Box<3>& box, const MarchingOptions& options)
      : samples_(samples),
        box_(box),
        options_(options),
        cell_(box.extent().maxCoeff() / std::max(options.resolution, 1)),
        h_(detail::marchingCellSize<3>(box, options.resolution)),
        region_(kGuardCells * std::sqrt(3.0) * cell_) {
    options_.review = [this](TriMesh& mesh, const GridLines<3>& lines) { review(mesh, lines); };
  }
  // marchingCubes with the review below; strays() are those of the contour it returns.
  TriMesh contour(const ImplicitField<3>& field, MarchingReport* report, int& dropped) {
    reviews_.clear();
    setField(field);
    MarchingReport local;
    MarchingReport& r = report ? *report : local;
    TriMesh mesh = marchingCubes(field, box_, options_, &r, &lines_);
    const bool refined = r.refinement == MarchingReport::Refinement::Refined;
    if (reviews_.empty()) reviews_.emplace_back();
    kept_ = refined ? reviews_.back() : reviews_.front();
    dropped_ = kept_.dropped;
    dropped = static_cast<int>(dropped_.size());
    return mesh;
  }
  const std::vector<Vec<3>>& strays() const { return kept_.strays; }
  const std::shared_ptr<const StrayTest>& planes() const { return planes_; }
  // dropWindingTips on the final contour.
  int dropTips(TriMesh& mesh) {
    if (vertexConnectedComponentCount(mesh) <= 1) return 0;
    return dropWindingTips(mesh, [&]() -> const CloudWinding<3>& { return *winding(); }, h_.norm());
  }
  // The field guarded around every stray found so far (those of the last contour added).
  std::unique_ptr<WindingGuardField> guard(const ImplicitField<3>& field) {
    for (const Vec<3>& p : kept_.strays) region_.add(p);
    return std::make_unique<WindingGuardField>(field, winding(), region_);
  }
  // The contour of `guard` (the last contour's field guarded about its strays): `mesh`, the last
  // contour, with the cells about those strays contoured again and reviewed (contour_patch.h),
  // or the whole grid again when they are more than kMaxPatchShare of it or a seam stays open.
  TriMesh contourAgain(const ImplicitField<3>& guard, TriMesh mesh, MarchingReport* report, int& dropped) {
    const std::vector<CellBlock> blocks = cellBlocksAround(lines_, kept_.strays, region_.radius());
    double cells = 0;
    for (const CellBlock& b : blocks)
      cells += double(b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]);
    const double all = double(lines_[0].size() - 1) * (lines_[1].size() - 1) * (lines_[2].size() - 1);
    std::optional<TriMesh> patched;
    reviews_.clear();
    setField(guard);
    if (cells <= kMaxPatchShare * all) patched = patchContour(mesh, guard, lines_, h_, blocks, options_);
    if (!patched) return contour(guard, report, dropped);
    kept_ = reviews_.back();
    dropped = patchDropped(blocks);
    return std::move(*patched);
  }

 private:
  // The samples' winding number, the plane test's (built by the first review, before any use).
  const std::shared_ptr<const CloudWinding<3>>& winding() const { return planes_->winding(); }
  // The field under review, and its grid form: the values marching cubes contours.
  void setField(const ImplicitField<3>& field) {
    field_ = &field;
    grid_ = field.forGridCells(h_.norm());
  }

  // Leaves out stray pieces and finds the strays of a contour on `lines`.
  void review(TriMesh& mesh, const GridLines<3>& lines) {
    if (!occupied_) {
      // Cells of one spacing for offTheirPlanes: its balls then touch at most 4³ and 6³ cells
      // whatever the grid (the occupancy cells shrink with it).
      planes_ = std::make_shared<const StrayTest>(samples_, box_, surfaceArea(mesh), options_.cancel);
      occupied_.emplace(samples_.points, box_.lo, occupancyCell());
    }
    Review r;
    const auto windingOf = [&]() -> const CloudWinding<3>& { return *winding(); };
    if (vertexConnectedComponentCount(mesh) > 1) r.dropped = dropStrayPieces(mesh, windingOf);
    r.strays = strayVertices(mesh, samples_, *occupied_, planes_->cells(), planes_->spacing(), windingOf);
    // Only strays a guard can still act on: new, and with f on the wrong side near them.
    const auto spent = [&](const Vec<3>& p) { return region_.contains(p) || !overruledNear(p, lines); };
    r.strays.erase(std::remove_if(r.strays.begin(), r.strays.end(), spent), r.strays.end());
    reviews_.push_back(std::move(r));
  }

  // The pieces left out of a patched contour: those left out before stay out, but those that meet a
  // block were contoured again and reviewed again (kept_, the patch's review, has them). Returns
  // how many.
  int patchDropped(const std::vector<CellBlock>& blocks) {
    const auto inBlock = [&](const Box<3>& piece) {
      return std::any_of(blocks.begin(), blocks.end(), [&](const CellBlock& b) { return overlap(piece, blockBox(b)); });
    };
    dropped_.erase(std::remove_if(dropped_.begin(), dropped_.end(), inBlock), dropped_.end());
    dropped_.insert(dropped_.end(), kept_.dropped.begin(), kept_.dropped.end());
    return static_cast<int>(dropped_.size());
  }

  // The block's cells in world coordinates (on the last contour's lines).
  Box<3> blockBox(const CellBlock& b) const {
    Box<3> box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = lines_[a][static_cast<std::size_t>(b.lo[a])];
      box.hi[a] = lines_[a][static_cast<std::size_t>(b.hi[a])];
    }
    return box;
  }

  // Half the grid's cell, at most kOccupancySpacing · √(A / N) for the contour's area A.
  double occupancyCell() const {
    const double spacing = planes_->spacing();
    return spacing > 0 ? std::min(0.5 * cell_, kOccupancySpacing * spacing) : 0.5 * cell_;
  }

  // Whether f is on the other side of the guard's winding number along p's grid edge (a quarter,
  // half, three quarters of the way to each end, and the ends) or at a corner of the cell-sized
  // cube about p: otherwise a guard there overrules nothing (a stray on a true surface whose
  // winding number is off ½, as beside a sharp concave edge). Along the edge, f is what the
  // contour took (the field's grid form, where it has data within a cell diagonal, as marching
  // cubes asks): a zero of f that strayed along an edge whose ends agree with the winding number
  // is seen there. At the corners, only where the field has data itself: a no-data stand-in deep
  // in the solid is positive.
  bool overruledNear(const Vec<3>& p, const GridLines<3>& lines) {
    const auto disagree = [&](const ImplicitField<3>& field, const Vec<3>& c) {
      return windingOverrules(winding()->at(c), field.evaluate(c));
    };
    const ImplicitField<3>& contoured = grid_ ? *grid_ : *field_;
    const GridEdge e = gridEdgeOf(lines, p);
    if (e.axis >= 0) {
      Vec<3> lo;
      for (int a = 0; a < 3; ++a) lo[a] = lines[a][static_cast<std::size_t>(e.at[a])];
      Vec<3> hi = lo;
      hi[e.axis] = lines[e.axis][static_cast<std::size_t>(e.at[e.axis]) + 1];
      for (const Vec<3>& end : {lo, hi})
        for (const double t : {0.25, 0.5, 0.75, 1.0}) {
          const Vec<3> c = p + t * (end - p);
          if (contoured.validNear(c, h_.norm()) && disagree(contoured, c)) return true;
        }
    }
    for (int k = 0; k < 8; ++k) {
      Vec<3> c = p;
      for (int a = 0; a < 3; ++a) c[a] += ((k >> a) & 1 ? 0.5 : -0.5) * cell_;
      if (field_->valid(c) && disagree(*field_, c)) return true;
    }
    return false;
  }

  struct Review {
    std::vector<Box<3>> dropped;  // the stray pieces left out, by their bounding boxes
    std::vector<Vec<3>> strays;  // stray vertices of what is left
  };

  const HermiteSamples<3>& samples_;
  Box<3> box_;
  MarchingOptions options_;
  std::optional<OccupiedCells> occupied_;  // built at the first review, from its contour's area
  std::shared_ptr<const StrayTest> planes_;  // its plane test, built with it (spacing √(A / N))
  double cell_;  // the contour grid's cell size (its longest axis's)
  Vec<3> h_;     // the uniform grid's cell
  GridLines<3> lines_;  // those of the last contour (refined ones when it was refined)
  GuardRegion region_;
  const ImplicitField<3>* field_ = nullptr;  // the field of the contour under review
  std::unique_ptr<ImplicitField<3>> grid_;    // its grid form (null: the field itself)
  std::vector<Box<3>> dropped_;  // the stray pieces left out of the contour kept, by their boxes
  std::vector<Review> reviews_;  // per contour of the last marchingCubes: the uniform one, then a refined one
  Review kept_;                  // the one of the contour it returned
};

}  // namespace

StrayTest::StrayTest(const HermiteSamples<3>& samples, const Box<3>& box, double area, const CancelToken* cancel)
    : samples_(samples),
      spacing_(std::sqrt(area / std::max(1, samples.size()))),
      bySpacing_(samples.points, box.lo, spacing_ > 0 ? spacing_ : box.extent().maxCoeff()),
      cancel_(cancel) {}

const std::shared_ptr<const CloudWinding<3>>& StrayTest::winding() const {
  if (!winding_) winding_ = std::make_shared<const CloudWinding<3>>(samples_.points, samples_.normals, cancel_);
  return winding_;
}

bool StrayTest::appliesTo(const ImplicitField<3>& field, const HermiteSamples<3>& samples) {
  return !field.everywhereValid() && samples.size() >= kGuardMinSamples;
}

std::vector<char> StrayTest::operator()(const Points<3>& X) const {
  std::vector<char> out(static_cast<std::size_t>(X.cols()), 0);
  if (!(spacing_ > 0)) return out;
  std::vector<Eigen::Index> off = offPlaneVertices(X, samples_, bySpacing_, spacing_);
  keepDecided(samples_, spacing_, X, off, [&]() -> const CloudWinding<3>& { return *winding(); });
  for (Eigen::Index v : off) out[static_cast<std::size_t>(v)] = 1;
  return out;
}

TriMesh contourWithoutStrays(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options,
                             const HermiteSamples<3>& samples, MarchingReport* report, StrayReport* stray,
                             std::unique_ptr<ImplicitField<3>>* guarded) {
  if (!StrayTest::appliesTo(field, samples)) return marchingCubes(field, box, options, report);
  StrayReport local;
  StrayReport& out = stray ? *stray : local;
  StrayContour contours(samples, box, options);
  TriMesh mesh = contours.contour(field, report, out.droppedPieces);
  out.strayVertices = static_cast<int>(contours.strays().size());
  out.tooMany = out.strayVertices > kMaxStrayShare * mesh.vertexCount();
  for (int round = 0; !out.tooMany && round < kGuardRounds && !contours.strays().empty(); ++round) {
    std::unique_ptr<WindingGuardField> guard = contours.guard(field);
    mesh = contours.contourAgain(*guard, std::move(mesh), report, out.droppedPieces);
    if (guarded) *guarded = std::move(guard);
    ++out.rounds;
  }
  const int tips = contours.dropTips(mesh);
  if (report) report->droppedTips += tips;
  if (!out.tooMany) out.planes = contours.planes();
  return mesh;
}

}  // namespace hermite
