#pragma once
// Partition-of-unity HRBF (scene key `fit.partition`; docs/maths.md, "Partition of unity"):
// local HRBF fits on the boxes of a quadtree/octree (pu_tree.h), blended by Shepard weights
//
//   f(x) = Σᵢ wᵢ(y) fᵢ(x) / Σᵢ wᵢ(y),   y = T⁻¹x  (T: the model's frame, identity until transformed)
//
// with wᵢ the C² tensor-product bump Πₖ (1 − tₖ²)³₊, tₖ = (yₖ − cₖ)/hₖ over support i (centre c,
// half-extents h). f, ∇f and the Hessian are C² wherever the local fits are. The smooth blend
// sums only the leaves whose box holds samples or borders one that does (MPU-style): where none of their supports reaches
// x, the field has "no data" (valid(x) false) and f is the constant noDataValue() > 0 ("outside"),
// so no zero set grows away from the data. Boxes whose support holds too few samples for their
// local system grow it (borrow neighbours) by `growth` steps until it does.

#include <memory>
#include <string>
#include <vector>

#include "core/pu/pu_data_reach.h"
#include "core/pu/pu_tree.h"
#include "core/rbf/hrbf.h"
#include "core/rbf/similarity_transform.h"

namespace hermite {

struct PuOptions {
  // Kernel, polynomial, smoothing, solver of every local fit; its cancel token is also polled box
  // by box (fitPu throws Cancelled).
  HrbfOptions local;
  int maxPointsPerBox = 20;     // ≥ 1: the default of `fit.partition.max_points_per_box`
  double boxSize = 0.0;         // ≥ 0; 0 = only the point-count rule
  double overlap = 1.5;         // ≥ 1: support = box scaled about its centre (1.5: 25 % margin per side)
  PuBlend blend = PuBlend::Smooth;
  // A support must hold at least this many samples (0 = automatic: enough for the polynomial
  // and at least min(maxPointsPerBox, 2·(Dim + 1)) so empty boxes do not fit from one sample).
  int minSamples = 0;
  double growth = 1.5;          // > 1: factor a too-sparse support grows by per step
  // A box whose support holds more than this many samples (0 = automatic: 3·maxPointsPerBox, at
  // least minSamples) is split further (pu_tree.h); where that cannot help (depth limit) the
  // support shrinks towards its box, though not below the box scaled by (1 + overlap)/2; a blended
  // empty box whose support still holds more is split (smooth blend, pu_blended_leaves.h). Solves
  // cost O(samples³): why 3· and not 6· or 2·, supportLimits in pu_leaf_fitter.h.
  int maxSupportSamples = 0;
  // c of the data reach (pu_data_reach.h; scene key `fit.partition.data_reach`): the smooth
  // blend has data within c·dₖ of a sample, dₖ its distance to the (2·Dim)-th nearest other
  // sample. 3 keeps every cell of a mesh as fine as the sampling, across the surface, inside.
  double dataReach = 3.0;
  // z of the edge test (pu_data_reach.h); 0 (the default) turns it off. With z > 0, y more
  // than half a reach from every sample and past the edge of the data — the samples reaching it
  // lie to one side, their mean offset along the tangent plane more than z standard deviations
  // of their offsets in that direction — has no data. At the edge of a uniformly sampled surface
  // the shift is 1.6 of them, at a convex box corner 1.6, at a sharp edge 0.7; 5 ends a sphere
  // cap half a reach past its rim instead of 0.8 and oni.pwn's neck at 10.5 % of the diagonal
  // instead of 17 %. Off by default: the tangent plane of a sample beside a thin limb's tip
  // meets the tip within the reach, and at grid steps near the spacing that opened holes there
  // (20 000 samples of the creature of test_pu_data_reach.cpp at 96³, even at z = 10).
  double edgeShift = 0.0;
  // β of the zero-set reach (pu_data_reach.h): a contour vertex has data only within β·dₖ
  // (capped) of a sample, where a grid point needs c·dₖ (`dataReach`). The zero set of data
  // sampled uniformly at random passes within β·dₖ of a sample except with probability about
  // e^(−k·β²) per point (k = 2·Dim neighbours in the disc of radius dₖ): 2 leaves no hole in a
  // million vertices, and an open surface ends 2 spacings past its last samples, not c.
  double vertexReach = 2.0;
};

// What the fit reports besides the model (`fit --json` "partition").
struct PuReport {
  int boxes = 0;
  int fittedBoxes = 0;     // leaves fitted and blended: holding samples or bordering a box that does
  int maxBoxSamples = 0;   // most samples in one leaf box
  int maxSupportSamples = 0;  // most samples in one local fit
  double meanSupportSamples = 0;
  int grownSupports = 0;   // supports grown to reach minSamples
  double fitMs = 0;        // tree + local fits, wall clock
  double treeMs = 0;
  int unknowns = 0;        // Σ over local systems
  double maxConditionEstimate = 0;  // worst local fit
  std::string solver;      // the local solver path most fits took
  std::vector<std::string> warnings;
};

template <int Dim>
struct PuRunScratch;  // evaluateBatch's per-thread buffers (pu_model.cpp)

template <int Dim>
class PuModel : public ImplicitField<Dim> {
 public:
  struct Leaf {
    Box<Dim> support;     // in frame coordinates: the leaf box scaled by `factor` about its centre
    double factor = 1.5;  // overlap, or more for a grown support, or less (≥ the floor) for a capped one
    // The local fit's samples: those in the support, and beside a sharp edge the few beyond it
    // that the first fit disagreed with (pu_leaf_fitter.h, refitAcrossEdges); 0 when not fitted.
    int samples = 0;
    // Whether the leaf is blended: its box holds samples or borders one that does (pu_blended_leaves.h,
    // blendedLeaves; the hard blend uses every leaf). f has no data where no blended support reaches.
    bool blended = true;
    HrbfModel<Dim> model;  // in world coordinates
  };

  PuModel() = default;
  PuModel(PuTree<Dim> tree, std::vector<Leaf> leaves, const PuOptions& options, const Similarity<Dim>& frame,
          PuDataReach<Dim> dataReach = {});

  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override;
  void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const override;
  // Smooth blend: Σᵢ (Gᵢ Fᵢ + F_max Gᵢ) / S_min + maxᵢ Lᵢ over the supports reaching the box, with
  // Gᵢ ≥ ‖∇wᵢ‖, Fᵢ ≥ |fᵢ| on the box, S_min ≤ Σ wᵢ; infinite for the hard blend (f jumps).
  // Zero where no data support reaches the box (f is constant there), infinite where the box
  // reaches the edge of the data (f may jump to noDataValue()).
  double lipschitzBound(const Box<Dim>& box) const override;
  // Some blended support reaches x (its box, with overlap 1) and so does a sample (dataReach());
  // always for the hard blend.
  bool valid(const Vec<Dim>& x) const override;
  // valid() with each sample's reach rᵢ widened to max(rᵢ, rᵢ/c + margin/q) for a grid of cell
  // diagonal `margin` (PuDataReach::reaches); a blended support must still reach x (f has a value).
  bool validNear(const Vec<Dim>& x, double margin) const override;
  // valid() with each sample's reach narrowed to PuOptions::vertexReach capped spacings
  // (PuDataReach::reaches): an open surface ends about that far past its last samples.
  bool validOnZeroSet(const Vec<Dim>& x) const override;
  bool everywhereValid() const override { return options_.blend == PuBlend::Hard; }
  void evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const override;
  // The smooth blend extended by up to a cell beyond its supports (PuNearField); null for the hard blend.
  std::unique_ptr<ImplicitField<Dim>> forGridCells(double cellDiagonal) const override;
  // The blended leaf whose support lies nearest to x (world) and within `margin` (world units) of
  // it, the smaller index on a tie; −1 when none.
  int nearestSupport(const Vec<Dim>& x, double margin) const;
  // Whether some blended support lies within `margin` (world units) of the world box.
  bool supportNear(const Box<Dim>& box, double margin) const;
  // f where there is no data: the root box's diagonal in world units (positive: "outside").
  double noDataValue() const { return noData_; }

  const PuTree<Dim>& tree() const { return tree_; }
  const std::vector<Leaf>& leaves() const { return leaves_; }
  const PuOptions& options() const { return options_; }
  // The samples' reach (frame coordinates): where valid() may be true. Empty for the hard blend.
  const PuDataReach<Dim>& dataReach() const { return dataReach_; }
  // World x = frame.apply(y) for frame coordinates y of boxes and supports.
  const Similarity<Dim>& frame() const { return frame_; }

  // Normalised weights Wᵢ(x) of the data leaves whose support contains y = T⁻¹x, for tests:
  // pairs (leaf, Wᵢ). Empty where no support reaches (no data, or overlap 1 on a face).
  std::vector<std::pair<int, double>> weights(const Vec<Dim>& x) const;

 private:
  void buildReach();
  template <class F>
  void forSupportsAt(const Vec<Dim>& y, F&& visit) const;
  // Whether accept(leaf) holds for some leaf whose support reaches y (the walk of forSupportsAt,
  // stopping at the first).
  template <class Accept>
  bool anySupportAt(const Vec<Dim>& y, Accept&& accept) const;
  template <class F>
  void forSupportsTouching(const Box<Dim>& b, F&& visit) const;
  // Whether columns begin … begin + count − 1 of X lie too far apart to share one walk of the tree.
  bool scatteredRun(const Points<Dim>& X, Eigen::Index begin, Eigen::Index count) const;
  // The world box in frame coordinates: the bounding box of its mapped corners.
  Box<Dim> frameBox(const Box<Dim>& box) const;
  // Every point of the frame box yb lies in the root and in a blended leaf box.
  bool coveredByData(const Box<Dim>& yb) const;
  // f and derivatives where no support reaches y: the own data box's fit (overlap 1 on a shared
  // face), else the no-data constant.
  double evaluateUncovered(const Vec<Dim>& x, const Vec<Dim>& y, Vec<Dim>* g, Mat<Dim>* H, bool* valid) const;
  // The smooth blend's f (and ∇f) at columns begin … begin + count − 1 of X (count ≤ the scratch's
  // run length): the supports touching their bounding box, each local fit at the points inside.
  void evaluateRun(const Points<Dim>& X, Eigen::Index begin, Eigen::Index count, Eigen::VectorXd& f, Points<Dim>* G,
                   PuRunScratch<Dim>& sc) const;
  // evaluate(), also saying whether x has data when `valid` is not null.
  double evaluateValid(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H, bool* valid) const;

  PuTree<Dim> tree_;
  std::vector<Leaf> leaves_;
  std::vector<Box<Dim>> reach_;  // per tree node: union of the supports of its blended leaves
  std::vector<char> allBlended_;  // per tree node: every leaf below it is blended
  PuOptions options_;
  Similarity<Dim> frame_;
  PuDataReach<Dim> dataReach_;
  bool identityFrame_ = true;
  double minFactor_ = 1.0;  // smallest support factor of a data leaf (the weight sum's lower bound needs it)
  double noData_ = 1.0;
  double typicalSupport_ = 0.0;  // median longest edge of the blended supports (frame units)
};

// Fits a PU model to validated samples. The tree is built on frame.applyInverse(points) (its
// boxes live in frame coordinates); the local fits use the samples as given, with the kernel
// radius scaled by frame.q. With the identity frame (the default) this is the plain PU fit; with
// the frame of a transform it is the re-solve of a transformed PU model on transformed data.
// Throws InputError for bad options, NumericalError when a local fit fails after growing.
template <int Dim>
PuModel<Dim> fitPu(const HermiteSamples<Dim>& samples, const PuOptions& options, PuReport* report = nullptr,
                   const Similarity<Dim>& frame = Similarity<Dim>());

// The PU model of the transformed data by coefficient updates: the tree is kept (boxes and
// supports move with T through the frame), every local model is transformed (transform.h).
// Equals fitPu on transformSamples(samples, T) with frame T·frame when the update is exact.
template <int Dim>
PuModel<Dim> transformPu(const PuModel<Dim>& model, const Similarity<Dim>& T);

// S ∘ T: x ↦ S(T(x)).
template <int Dim>
Similarity<Dim> composeSimilarity(const Similarity<Dim>& S, const Similarity<Dim>& T);

extern template class PuModel<2>;
extern template class PuModel<3>;

}  // namespace hermite
