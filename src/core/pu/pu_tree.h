#pragma once
// The box tree of a partition-of-unity fit (scene key `fit.partition`; docs/maths.md, Partition of unity): a quadtree (2D) or
// octree (3D) over the samples' bounding box (grown by a small margin so no sample sits on the
// root's faces). A box holding samples is split into 2^Dim equal children while it holds more
// than `maxPointsPerBox` samples or, when `boxSize` > 0, while its longest edge exceeds
// `boxSize`, or while its support holds more than `maxSupportSamples` (when set; empty boxes only
// with `splitEmpty`); other empty boxes are never split. The leaves tile the root box.

#include <string_view>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/enum_names.h"
#include "core/base/geometry.h"

namespace hermite {

enum class PuBlend {
  Smooth,  // Shepard blend of C² bumps (the method)
  Hard,    // each point takes its own box's fit: a teaching demo of the seams box division leaves
};

inline constexpr EnumName<PuBlend> kPuBlendNames[] = {{"smooth", PuBlend::Smooth}, {"hard", PuBlend::Hard}};
std::string_view puBlendName(PuBlend b);
PuBlend parsePuBlend(std::string_view s);  // throws InputError


struct PuTreeOptions {
  int maxPointsPerBox = 20;  // ≥ 1
  double boxSize = 0.0;      // ≥ 0; 0 = only the point-count rule
  int maxDepth = 21;         // safety net for coincident samples (they cannot be separated)
  // Also split a box (empty ones too) while its support — the box scaled by `overlap` — holds
  // more than this many samples (0 = off): a big box beside the surface would otherwise fit
  // thousands of samples from its margin.
  int maxSupportSamples = 0;
  double overlap = 1.5;
  // Whether the support rule splits empty boxes too: the hard blend fits every box; the smooth
  // blend fits only the empty boxes beside the data, and splits those crowded itself
  // (pu_blended_leaves.cpp, splitCrowdedBlended).
  bool splitEmpty = true;
  // Polled every few hundred splits (Cancelled); a million samples take seconds to subdivide.
  const CancelToken* cancel = nullptr;
};

template <int Dim>
class PuTree {
 public:
  static constexpr int kChildren = 1 << Dim;

  struct Node {
    Box<Dim> box;
    int firstChild = -1;  // children are kChildren consecutive nodes; -1 for a leaf
    int leaf = -1;        // index into leaves() for a leaf, else -1
    int begin = 0;        // samples of the node: order()[begin, end)
    int end = 0;
    int depth = 0;
    int parent = -1;      // -1 for the root
  };

  PuTree() = default;
  // Builds the tree over the columns of `points` (Dim × N, N ≥ 1). InputError for bad options.
  PuTree(const Points<Dim>& points, const PuTreeOptions& options);

  const std::vector<Node>& nodes() const { return nodes_; }
  const Node& node(int i) const { return nodes_[i]; }
  const Box<Dim>& root() const { return nodes_.front().box; }
  // Node index of every leaf, in depth-first order.
  const std::vector<int>& leaves() const { return leaves_; }
  int leafCount() const { return static_cast<int>(leaves_.size()); }
  const Box<Dim>& leafBox(int leaf) const { return nodes_[leaves_[leaf]].box; }
  int leafSampleCount(int leaf) const { return nodes_[leaves_[leaf]].end - nodes_[leaves_[leaf]].begin; }
  // Sample indices sorted so every node's samples are contiguous.
  const std::vector<int>& order() const { return order_; }
  // The tree's points in that order (Dim × N): column j is points.col(order()[j]), so a node's
  // samples lie side by side in memory for the box queries.
  const Points<Dim>& sortedPoints() const { return sorted_; }

  // The leaf whose box contains y (y is clamped to the root box first; ties on shared faces go
  // to the upper child).
  int locateLeaf(const Vec<Dim>& y) const;

  // The positions j in order() of the tree's samples inside the closed box `query`
  // (sortedPoints().col(j) is the sample, order()[j] its index). The walk starts at the nearest
  // ancestor of node `near` (itself included) whose box holds `query` strictly inside — every
  // sample in `query` lies in that node — so a query about a leaf skips the walk down from the
  // root; the samples and their order are those of a walk from the root.
  void positionsInBox(const Box<Dim>& query, std::vector<int>& out, int near = 0) const;
  // The k-th smallest of the samples' scaled L∞ distances maxₖ |yₖ − cₖ| / hₖ from the centre c
  // of `box` (half-extents h): `box` scaled about c by that factor just holds its k nearest
  // samples. +∞ when the tree holds fewer than k (k ≥ 1). A nearest-first walk that skips nodes
  // farther than the k-th distance found so far.
  double kthScaledDistance(const Box<Dim>& box, int k) const;
  // How many samples lie in `query`, counting stops above `limit`.
  int countInBox(const Box<Dim>& query, int limit, int near = 0) const;
  // The nearest ancestor of node `near` (itself included) whose box holds `query` strictly
  // inside, or the root.
  int enclosingNode(const Box<Dim>& query, int near) const;

  // Splits each given leaf that holds no samples into kChildren empty children (leaves with
  // samples, or at depth `maxDepth`, stay). Leaf indices change: leaves() is listed afresh;
  // sample order and existing node indices do not.
  void splitEmptyLeaves(const std::vector<int>& leafIds, int maxDepth = 21);

 private:
  void listLeaves();  // leaves_ in depth-first order
  // Splits node `id` into kChildren children, its samples bucketed by child (bit k set ⇔
  // coordinate k ≥ the centre's); returns the first child. `scratch` is reused between calls.
  struct SplitScratch {  // reused between splits
    std::vector<int> order;
    Points<Dim> points;
  };
  int splitNode(int id, SplitScratch& scratch);
  // Pass 1: the `fit.partition` rules (docs/scene-format.md) from the root.
  void splitByRules(const PuTreeOptions& options, SplitScratch& scratch);
  // Pass 2, on the complete tree (so support queries are fast): leaves whose support at
  // `overlap` holds more than maxSupportSamples samples split further.
  void splitCrowdedSupports(const PuTreeOptions& options, SplitScratch& scratch);
  // Appends the kChildren children of node `id` (its box split at the centre), child ch holding
  // the samples order_[begin[ch], end[ch]); returns the first.
  int addChildren(int id, const int (&begin)[kChildren], const int (&end)[kChildren]);
  // Calls take(j, inside) for the position j in order() of every sample of a leaf that meets
  // `query` (inside: whether `query` holds it), takeRange(begin, end) for a whole node's range
  // inside `query`; stops when done() turns true. Children's boxes are made from their parent's
  // as splitNode made them (the same numbers), so the walk reads only spans_ of the nodes.
  template <class Take, class TakeRange, class Done>
  void visitInBox(const Box<Dim>& query, int near, Take&& take, TakeRange&& takeRange, Done&& done) const;

  struct Span {  // what a walk reads of a node: its children and its samples
    int firstChild = -1;
    int begin = 0;
    int end = 0;
  };

  std::vector<Node> nodes_;
  std::vector<Span> spans_;  // per node, as in nodes_
  std::vector<int> leaves_;
  std::vector<int> order_;
  Points<Dim> sorted_;  // the points in order_ (sortedPoints())
};

// The box b scaled by `factor` about its centre.
template <int Dim>
Box<Dim> scaledBox(const Box<Dim>& b, double factor) {
  const Vec<Dim> c = b.center();
  const Vec<Dim> h = 0.5 * factor * b.extent();
  return Box<Dim>{c - h, c + h};
}

// The scaled L∞ distance maxₖ |yₖ − cₖ| / hₖ of y from a box's centre c, given invH = 1 / its
// half-extents hₖ: the factor by which the box, scaled about c, just reaches y. The one formula
// of PuTree::kthScaledDistance and of the local fits' support factors, so that they agree bit for bit.
template <int Dim>
double scaledDistance(const Vec<Dim>& y, const Vec<Dim>& c, const Vec<Dim>& invH) {
  return ((y - c).cwiseAbs().cwiseProduct(invH)).maxCoeff();
}

template <int Dim>
bool boxesIntersect(const Box<Dim>& a, const Box<Dim>& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

extern template class PuTree<2>;
extern template class PuTree<3>;

}  // namespace hermite
