#include "core/pu/pu_tree.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "core/base/errors.h"

namespace hermite {

namespace {

// Child ch of a box split at c: bit k of ch picks the upper half along axis k.
template <int Dim>
Box<Dim> childBox(const Box<Dim>& box, const Vec<Dim>& c, int ch) {
  Box<Dim> child = box;
  for (int k = 0; k < Dim; ++k) {
    const bool upper = (ch >> k) & 1;
    child.lo(k) = upper ? c(k) : box.lo(k);
    child.hi(k) = upper ? box.hi(k) : c(k);
  }
  return child;
}

}  // namespace

std::string_view puBlendName(PuBlend b) { return nameIn<PuBlend>(kPuBlendNames, b); }

PuBlend parsePuBlend(std::string_view s) {
  if (const auto value = valueIn<PuBlend>(kPuBlendNames, s)) return *value;
  throw InputError("unknown blend '" + std::string(s) + "' (expected " + std::string(kPuBlendNames[0].name) + " or " +
                   std::string(kPuBlendNames[1].name) + ")");
}


template <int Dim>
PuTree<Dim>::PuTree(const Points<Dim>& points, const PuTreeOptions& options) {
  if (points.cols() < 1) throw InputError("partition: no samples to subdivide");
  if (options.maxPointsPerBox < 1)
    throw InputError("partition: max_points_per_box must be >= 1 (got " + std::to_string(options.maxPointsPerBox) + ")");
  if (!(options.boxSize >= 0))
    throw InputError("partition: box_size must be >= 0 (got " + std::to_string(options.boxSize) + ")");
  const int n = static_cast<int>(points.cols());
  Box<Dim> root = boundingBox<Dim>(points);
  // 5 % of the largest extent on every side (1 for a single point): no sample on the root's
  // faces, and flat data still gets boxes with volume.
  const double extent = root.extent().maxCoeff();
  const double margin = 0.05 * (extent > 0 ? extent : 1.0);
  root.lo.array() -= margin;
  root.hi.array() += margin;

  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(2 * static_cast<std::size_t>(n / std::max(1, options.maxPointsPerBox) + 1) * kChildren);
  nodes_.push_back(Node{root, -1, -1, 0, n, 0});
  std::vector<int> scratch;
  splitByRules(points, options, scratch);
  if (options.maxSupportSamples > 0) splitCrowdedSupports(points, options, scratch);
  listLeaves();
}

template <int Dim>
int PuTree<Dim>::splitNode(const Points<Dim>& points, int id, std::vector<int>& scratch) {
  const Node nd = nodes_[id];
  const Vec<Dim> c = nd.box.center();
  int counts[kChildren] = {};
  auto childOf = [&](int s) {
    int ch = 0;
    for (int k = 0; k < Dim; ++k)
      if (points(k, s) >= c(k)) ch |= 1 << k;
    return ch;
  };
  for (int i = nd.begin; i < nd.end; ++i) ++counts[childOf(order_[i])];
  int offsets[kChildren];
  offsets[0] = nd.begin;
  for (int ch = 1; ch < kChildren; ++ch) offsets[ch] = offsets[ch - 1] + counts[ch - 1];
  scratch.assign(order_.begin() + nd.begin, order_.begin() + nd.end);
  int fill[kChildren];
  std::copy(offsets, offsets + kChildren, fill);
  for (int s : scratch) order_[fill[childOf(s)]++] = s;
  const int first = static_cast<int>(nodes_.size());
  nodes_[id].firstChild = first;
  for (int ch = 0; ch < kChildren; ++ch) {
    Node child;
    child.box = childBox(nd.box, c, ch);
    child.begin = offsets[ch];
    child.end = offsets[ch] + counts[ch];
    child.depth = nd.depth + 1;
    nodes_.push_back(child);
  }
  return first;
}

template <int Dim>
void PuTree<Dim>::splitByRules(const Points<Dim>& points, const PuTreeOptions& options, std::vector<int>& scratch) {
  std::vector<int> stack{0};
  int splits = 0;
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const Node& nd = nodes_[id];
    const int count = nd.end - nd.begin;
    const bool tooMany = count > options.maxPointsPerBox;
    const bool tooBig = options.boxSize > 0 && nd.box.extent().maxCoeff() > options.boxSize;
    if (count == 0 || !(tooMany || tooBig) || nd.depth >= options.maxDepth) continue;
    if (++splits % 256 == 0) throwIfCancelled(options.cancel);
    const int first = splitNode(points, id, scratch);
    for (int ch = kChildren - 1; ch >= 0; --ch) stack.push_back(first + ch);
  }
}

// Level by level: the crowding of every candidate is counted in parallel (countInBox reads the
// tree, which no thread changes meanwhile), then the crowded ones split one after another. A
// support's count does not depend on the tree's shape, and a split reorders only its own node's
// range of order_, so the tree is the one a depth-first pass splits, up to the numbering of nodes
// (leaves() is listed depth first either way).
template <int Dim>
void PuTree<Dim>::splitCrowdedSupports(const Points<Dim>& points, const PuTreeOptions& options,
                                       std::vector<int>& scratch) {
  std::vector<int> candidates, next;
  for (int id = 0; id < static_cast<int>(nodes_.size()); ++id)
    if (nodes_[id].firstChild < 0) candidates.push_back(id);
  const int limit = options.maxSupportSamples;
  std::vector<char> crowded;
  while (!candidates.empty()) {
    const int m = static_cast<int>(candidates.size());
    crowded.assign(static_cast<std::size_t>(m), 0);
#pragma omp parallel for schedule(dynamic, 256)
    for (int i = 0; i < m; ++i) {
      if (options.cancel && options.cancel->cancelled()) continue;  // polled per box: most of this pass's work
      const Node& nd = nodes_[static_cast<std::size_t>(candidates[static_cast<std::size_t>(i)])];
      if (nd.depth >= options.maxDepth || (!options.splitEmpty && nd.begin == nd.end)) continue;
      crowded[static_cast<std::size_t>(i)] = countInBox(points, scaledBox<Dim>(nd.box, options.overlap), limit) > limit;
    }
    throwIfCancelled(options.cancel);
    next.clear();
    for (int i = 0; i < m; ++i) {
      if (!crowded[static_cast<std::size_t>(i)]) continue;
      const int first = splitNode(points, candidates[static_cast<std::size_t>(i)], scratch);
      for (int ch = 0; ch < kChildren; ++ch) next.push_back(first + ch);
    }
    candidates.swap(next);
  }
}

template <int Dim>
void PuTree<Dim>::listLeaves() {
  // Leaves in depth-first order (children before later siblings) for locality.
  leaves_.clear();
  std::vector<int> stack(1, 0);
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    if (nodes_[id].firstChild < 0) {
      nodes_[id].leaf = static_cast<int>(leaves_.size());
      leaves_.push_back(id);
    } else {
      for (int ch = kChildren - 1; ch >= 0; --ch) stack.push_back(nodes_[id].firstChild + ch);
    }
  }
}

template <int Dim>
void PuTree<Dim>::splitEmptyLeaves(const std::vector<int>& leafIds, int maxDepth) {
  for (int leaf : leafIds) {
    const int id = leaves_[static_cast<std::size_t>(leaf)];
    const Node nd = nodes_[static_cast<std::size_t>(id)];
    if (nd.begin != nd.end || nd.firstChild >= 0 || nd.depth >= maxDepth) continue;
    const Vec<Dim> c = nd.box.center();
    nodes_[static_cast<std::size_t>(id)].firstChild = static_cast<int>(nodes_.size());
    nodes_[static_cast<std::size_t>(id)].leaf = -1;
    for (int ch = 0; ch < kChildren; ++ch) {
      Node child;
      child.box = childBox(nd.box, c, ch);
      child.begin = child.end = nd.begin;
      child.depth = nd.depth + 1;
      nodes_.push_back(child);
    }
  }
  listLeaves();
}

template <int Dim>
int PuTree<Dim>::locateLeaf(const Vec<Dim>& y) const {
  const Vec<Dim> p = y.cwiseMax(root().lo).cwiseMin(root().hi);
  int id = 0;
  while (nodes_[id].firstChild >= 0) {
    const Vec<Dim> c = nodes_[id].box.center();
    int ch = 0;
    for (int k = 0; k < Dim; ++k)
      if (p(k) >= c(k)) ch |= 1 << k;
    id = nodes_[id].firstChild + ch;
  }
  return nodes_[id].leaf;
}

template <int Dim>
int PuTree<Dim>::countInBox(const Points<Dim>& points, const Box<Dim>& query, int limit) const {
  int count = 0;
  int stack[64 * kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && count <= limit) {
    const Node& nd = nodes_[stack[--top]];
    if (nd.begin == nd.end || !boxesIntersect<Dim>(nd.box, query)) continue;
    const bool inside = (nd.box.lo.array() >= query.lo.array()).all() && (nd.box.hi.array() <= query.hi.array()).all();
    if (inside) {
      count += nd.end - nd.begin;
    } else if (nd.firstChild < 0) {
      for (int i = nd.begin; i < nd.end; ++i)
        if (query.contains(points.col(order_[i]))) ++count;
    } else {
      for (int ch = 0; ch < kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    }
  }
  return count;
}

template <int Dim>
void PuTree<Dim>::samplesInBox(const Points<Dim>& points, const Box<Dim>& query, std::vector<int>& out) const {
  out.clear();
  int stack[64 * kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& nd = nodes_[stack[--top]];
    if (nd.begin == nd.end || !boxesIntersect<Dim>(nd.box, query)) continue;
    const bool inside = (nd.box.lo.array() >= query.lo.array()).all() && (nd.box.hi.array() <= query.hi.array()).all();
    if (inside) {
      out.insert(out.end(), order_.begin() + nd.begin, order_.begin() + nd.end);
    } else if (nd.firstChild < 0) {
      for (int i = nd.begin; i < nd.end; ++i)
        if (query.contains(points.col(order_[i]))) out.push_back(order_[i]);
    } else {
      for (int ch = 0; ch < kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    }
  }
}

template class PuTree<2>;
template class PuTree<3>;

}  // namespace hermite
