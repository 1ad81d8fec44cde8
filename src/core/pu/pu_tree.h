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
  // blend fits only boxes holding samples, so splitting empty ones would only add boxes.
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

  // The leaf whose box contains y (y is clamped to the root box first; ties on shared faces go
  // to the upper child).
  int locateLeaf(const Vec<Dim>& y) const;

  // Indices of the samples of `points` (the tree's points) inside the closed box `query`.
  void samplesInBox(const Points<Dim>& points, const Box<Dim>& query, std::vector<int>& out) const;
  // How many samples lie in `query`, counting stops above `limit`.
  int countInBox(const Points<Dim>& points, const Box<Dim>& query, int limit) const;

  // Splits each given leaf that holds no samples into kChildren empty children (leaves with
  // samples, or at depth `maxDepth`, stay). Leaf indices change: leaves() is listed afresh;
  // sample order and existing node indices do not.
  void splitEmptyLeaves(const std::vector<int>& leafIds, int maxDepth = 21);

 private:
  void listLeaves();  // leaves_ in depth-first order
  // Splits node `id` into kChildren children, its samples bucketed by child (bit k set ⇔
  // coordinate k ≥ the centre's); returns the first child. `scratch` is reused between calls.
  int splitNode(const Points<Dim>& points, int id, std::vector<int>& scratch);
  // Pass 1: the `fit.partition` rules (docs/scene-format.md) from the root.
  void splitByRules(const Points<Dim>& points, const PuTreeOptions& options, std::vector<int>& scratch);
  // Pass 2, on the complete tree (so support queries are fast): leaves whose support at
  // `overlap` holds more than maxSupportSamples samples split further.
  void splitCrowdedSupports(const Points<Dim>& points, const PuTreeOptions& options, std::vector<int>& scratch);

  std::vector<Node> nodes_;
  std::vector<int> leaves_;
  std::vector<int> order_;
};

// The box b scaled by `factor` about its centre.
template <int Dim>
Box<Dim> scaledBox(const Box<Dim>& b, double factor) {
  const Vec<Dim> c = b.center();
  const Vec<Dim> h = 0.5 * factor * b.extent();
  return Box<Dim>{c - h, c + h};
}

template <int Dim>
bool boxesIntersect(const Box<Dim>& a, const Box<Dim>& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

extern template class PuTree<2>;
extern template class PuTree<3>;

}  // namespace hermite
