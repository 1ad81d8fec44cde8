#include "core/pu/pu_tree.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <string>

#include "core/base/errors.h"

namespace hermite {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

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
  sorted_ = points;
  nodes_.reserve(2 * static_cast<std::size_t>(n / std::max(1, options.maxPointsPerBox) + 1) * kChildren);
  nodes_.push_back(Node{root, -1, -1, 0, n, 0, -1});
  spans_.push_back(Span{-1, 0, n});
  SplitScratch scratch;
  splitByRules(options, scratch);
  if (options.maxSupportSamples > 0) splitCrowdedSupports(options, scratch);
  listLeaves();
}

template <int Dim>
int PuTree<Dim>::splitNode(int id, SplitScratch& scratch) {
  const Node nd = nodes_[id];
  const Vec<Dim> c = nd.box.center();
  int counts[kChildren] = {};
  auto childOf = [&](const auto& p) {
    int ch = 0;
    for (int k = 0; k < Dim; ++k)
      if (p(k) >= c(k)) ch |= 1 << k;
    return ch;
  };
  for (int i = nd.begin; i < nd.end; ++i) ++counts[childOf(sorted_.col(i))];
  int offsets[kChildren];
  offsets[0] = nd.begin;
  for (int ch = 1; ch < kChildren; ++ch) offsets[ch] = offsets[ch - 1] + counts[ch - 1];
  const int count = nd.end - nd.begin;
  scratch.order.assign(order_.begin() + nd.begin, order_.begin() + nd.end);
  scratch.points = sorted_.middleCols(nd.begin, count);
  int fill[kChildren];
  std::copy(offsets, offsets + kChildren, fill);
  for (int i = 0; i < count; ++i) {
    const int to = fill[childOf(scratch.points.col(i))]++;
    order_[static_cast<std::size_t>(to)] = scratch.order[static_cast<std::size_t>(i)];
    sorted_.col(to) = scratch.points.col(i);
  }
  int ends[kChildren];
  for (int ch = 0; ch < kChildren; ++ch) ends[ch] = offsets[ch] + counts[ch];
  return addChildren(id, offsets, ends);
}

template <int Dim>
int PuTree<Dim>::addChildren(int id, const int (&begin)[kChildren], const int (&end)[kChildren]) {
  const Node nd = nodes_[static_cast<std::size_t>(id)];
  const Vec<Dim> c = nd.box.center();
  const int first = static_cast<int>(nodes_.size());
  nodes_[static_cast<std::size_t>(id)].firstChild = first;
  nodes_[static_cast<std::size_t>(id)].leaf = -1;
  spans_[static_cast<std::size_t>(id)].firstChild = first;
  for (int ch = 0; ch < kChildren; ++ch) {
    Node child;
    child.box = childBox(nd.box, c, ch);
    child.begin = begin[ch];
    child.end = end[ch];
    child.depth = nd.depth + 1;
    child.parent = id;
    nodes_.push_back(child);
    spans_.push_back(Span{-1, begin[ch], end[ch]});
  }
  return first;
}

template <int Dim>
void PuTree<Dim>::splitByRules(const PuTreeOptions& options, SplitScratch& scratch) {
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
    const int first = splitNode(id, scratch);
    for (int ch = kChildren - 1; ch >= 0; --ch) stack.push_back(first + ch);
  }
}

// Level by level: the crowding of every candidate is counted in parallel (countInBox reads the
// tree, which no thread changes meanwhile), then the crowded ones split one after another. A
// support's count does not depend on the tree's shape, and a split reorders only its own node's
// range of order_, so the tree is the one a depth-first pass splits, up to the numbering of nodes
// (leaves() is listed depth first either way).
template <int Dim>
void PuTree<Dim>::splitCrowdedSupports(const PuTreeOptions& options, SplitScratch& scratch) {
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
      const int id = candidates[static_cast<std::size_t>(i)];
      const Node& nd = nodes_[static_cast<std::size_t>(id)];
      if (nd.depth >= options.maxDepth || (!options.splitEmpty && nd.begin == nd.end)) continue;
      crowded[static_cast<std::size_t>(i)] = countInBox(scaledBox<Dim>(nd.box, options.overlap), limit, id) > limit;
    }
    throwIfCancelled(options.cancel);
    next.clear();
    for (int i = 0; i < m; ++i) {
      if (!crowded[static_cast<std::size_t>(i)]) continue;
      const int first = splitNode(candidates[static_cast<std::size_t>(i)], scratch);
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
    int at[kChildren];
    std::fill(at, at + kChildren, nd.begin);
    addChildren(id, at, at);
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
int PuTree<Dim>::enclosingNode(const Box<Dim>& query, int near) const {
  int id = near;
  while (id > 0) {
    const Box<Dim>& b = nodes_[static_cast<std::size_t>(id)].box;
    if ((b.lo.array() < query.lo.array()).all() && (query.hi.array() < b.hi.array()).all()) break;
    id = nodes_[static_cast<std::size_t>(id)].parent;
  }
  return id;
}

template <int Dim>
int PuTree<Dim>::countInBox(const Box<Dim>& query, int limit, int near) const {
  int count = 0;
  visitInBox(
      query, near, [&](int, bool in) { count += in ? 1 : 0; }, [&](int begin, int end) { count += end - begin; },
      [&] { return count > limit; });
  return count;
}

// The children a node's walk goes on to, with a node's box split at its centre c: on axis k the
// lower half meets the query when q.lo ≤ c, the upper when c ≤ q.hi (the node itself meets it),
// and a child meets the query when its half does on every axis — boxesIntersect of the child's
// box, without making the box of every child. Likewise for a child inside the query.
template <int Dim>
template <class Take, class TakeRange, class Done>
void PuTree<Dim>::visitInBox(const Box<Dim>& query, int near, Take&& take, TakeRange&& takeRange, Done&& done) const {
  struct Item {  // not Box: its initialised members would clear the whole stack on every call
    int id;
    bool inside;
    Vec<Dim> lo, hi;
  };
  constexpr unsigned kAll = kChildren - 1;
  Item stack[64 * kChildren];
  int top = 0;
  const int start = enclosingNode(query, near);
  const Span& s0 = spans_[static_cast<std::size_t>(start)];
  const Box<Dim>& b0 = nodes_[static_cast<std::size_t>(start)].box;
  const bool inside0 = (b0.lo.array() >= query.lo.array()).all() && (b0.hi.array() <= query.hi.array()).all();
  if (s0.begin != s0.end && boxesIntersect<Dim>(b0, query)) stack[top++] = Item{start, inside0, b0.lo, b0.hi};
  while (top > 0 && !done()) {
    const Item it = stack[--top];
    const Span& sp = spans_[static_cast<std::size_t>(it.id)];
    if (it.inside) {
      takeRange(sp.begin, sp.end);
    } else if (sp.firstChild < 0) {
      for (int i = sp.begin; i < sp.end; ++i) take(i, query.contains(sorted_.col(i)));
    } else {
      const Vec<Dim> c = 0.5 * (it.lo + it.hi);  // Box::center(), as splitNode splits
      unsigned meetLo = 0, meetHi = 0, inLo = 0, inHi = 0;
      for (int k = 0; k < Dim; ++k) {
        meetLo |= unsigned(query.lo(k) <= c(k)) << k;
        meetHi |= unsigned(c(k) <= query.hi(k)) << k;
        inLo |= unsigned(it.lo(k) >= query.lo(k) && c(k) <= query.hi(k)) << k;
        inHi |= unsigned(c(k) >= query.lo(k) && it.hi(k) <= query.hi(k)) << k;
      }
      for (int ch = 0; ch < kChildren; ++ch) {
        const unsigned up = unsigned(ch), down = ~up & kAll;
        const Span& cs = spans_[static_cast<std::size_t>(sp.firstChild + ch)];
        if (((meetHi & up) | (meetLo & down)) != kAll || cs.begin == cs.end) continue;
        Item& child = stack[top++];
        child.id = sp.firstChild + ch;
        child.inside = ((inHi & up) | (inLo & down)) == kAll;
        for (int k = 0; k < Dim; ++k) {
          const bool upper = (up >> k) & 1u;
          child.lo(k) = upper ? c(k) : it.lo(k);
          child.hi(k) = upper ? it.hi(k) : c(k);
        }
      }
    }
  }
}

// Appends without a branch per sample: every candidate is written, and the end moves on only
// past those inside (which of them are is unpredictable at a support's faces).
template <int Dim>
void PuTree<Dim>::positionsInBox(const Box<Dim>& query, std::vector<int>& out, int near) const {
  out.clear();
  std::size_t size = 0;
  visitInBox(
      query, near,
      [&](int j, bool in) {
        if (size == out.size()) out.resize(std::max<std::size_t>(64, 2 * size));
        out[size] = j;
        size += in ? 1 : 0;
      },
      [&](int begin, int end) {
        out.resize(size + static_cast<std::size_t>(end - begin));
        std::iota(out.begin() + static_cast<std::ptrdiff_t>(size), out.end(), begin);
        size = out.size();
      },
      [] { return false; });
  out.resize(size);
}

template <int Dim>
double PuTree<Dim>::kthScaledDistance(const Box<Dim>& box, int k) const {
  const Vec<Dim> c = box.center();
  const Vec<Dim> invH = (0.5 * box.extent()).cwiseInverse();
  thread_local std::vector<double> best;  // the k smallest so far, ascending
  best.clear();
  const auto bound = [&] { return static_cast<int>(best.size()) < k ? kInfinity : best.back(); };
  const auto nodeDistance = [&](int id) {  // no sample of the node lies nearer
    const Box<Dim>& b = nodes_[static_cast<std::size_t>(id)].box;
    return ((b.lo - c).cwiseMax(c - b.hi).cwiseMax(0.0).cwiseProduct(invH)).maxCoeff();
  };
  int stack[64 * kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    const Span& sp = spans_[static_cast<std::size_t>(id)];
    if (sp.begin == sp.end || nodeDistance(id) > bound()) continue;
    if (sp.firstChild >= 0) {  // the nearest child on top
      std::array<std::pair<double, int>, kChildren> order;
      for (int ch = 0; ch < kChildren; ++ch) order[ch] = {nodeDistance(sp.firstChild + ch), sp.firstChild + ch};
      std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
      for (const auto& [d, child] : order) stack[top++] = child;
      continue;
    }
    for (int j = sp.begin; j < sp.end; ++j) {
      const double d = scaledDistance<Dim>(sorted_.col(j), c, invH);
      if (static_cast<int>(best.size()) == k && !(d < best.back())) continue;
      if (static_cast<int>(best.size()) == k) best.pop_back();
      best.insert(std::upper_bound(best.begin(), best.end(), d), d);
    }
  }
  return bound();
}

template class PuTree<2>;
template class PuTree<3>;

}  // namespace hermite
