// The dynamic AABB tree of the World's broad phase (see aabb_tree.hpp).
//
// Insertion walks down from the root choosing, at each internal node, between making the new leaf
// a sibling of that node and descending into one of its children, by the increase of surface area
// each choice causes (the usual cost model of bounding-volume trees: the chance that a random query
// box overlaps a node grows with its area). On the way back up, nodes whose children's heights
// differ by more than one are rotated (as in an AVL tree), so the height stays O(log n) whatever
// the insertion order. Rebuilds and refits: aabb_tree.hpp.
#include "world/aabb_tree.hpp"

#include <antcd/tolerances.hpp>

#include "util/float_bounds.hpp"
#include "util/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

namespace antcd::detail {

void AabbTree::set_node_box(Node& n, const Aabb& b) {
#if defined(__SSE2__)
  // float_below() (util/float_bounds.hpp) on the four lanes (min x, min y, min z, -max x) and on
  // (-max y, -max z): the same IEEE operations lane by lane, so the same floats (this runs for
  // every moved object of a frame).
  const __m128d limit = _mm_set1_pd(std::numeric_limits<float>::max());
  const __m128d sign = _mm_set1_pd(-0.0);
  const auto to_float = [&](__m128d x) {
    return _mm_cvtpd_ps(_mm_min_pd(_mm_max_pd(x, _mm_xor_pd(limit, sign)), limit));
  };
  const __m128d mxy = _mm_loadu_pd(b.min.data());
  const __m128d mz_hx =
      _mm_unpacklo_pd(_mm_load_sd(b.min.data() + 2), _mm_xor_pd(_mm_load_sd(b.max.data()), sign));
  const __m128d hyz = _mm_xor_pd(_mm_loadu_pd(b.max.data() + 1), sign);
  const __m128 f1 = _mm_movelh_ps(to_float(mxy), to_float(mz_hx));
  const __m128 f2 = to_float(hyz);
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 ulp = _mm_set1_ps(0x1p-23F);
  const __m128 tiny = _mm_set1_ps(std::numeric_limits<float>::min());
  const auto down4 = [&](__m128 f) {
    return _mm_sub_ps(f, _mm_add_ps(_mm_mul_ps(_mm_and_ps(f, abs_mask), ulp), tiny));
  };
  alignas(16) float d1[4];
  alignas(16) float d2[4];
  _mm_store_ps(d1, down4(f1));
  _mm_store_ps(d2, down4(f2));
  n.lo[0] = d1[0];
  n.lo[1] = d1[1];
  n.lo[2] = d1[2];
  n.hi[0] = -d1[3];
  n.hi[1] = -d2[0];
  n.hi[2] = -d2[1];
#else
  for (int k = 0; k < 3; ++k) {
    n.lo[k] = float_below(b.min[k]);
    n.hi[k] = float_above(b.max[k]);
  }
#endif
}

void AabbTree::merge_into(Node& n, const Node& a, const Node& b) {
  for (int k = 0; k < 3; ++k) {
    n.lo[k] = std::min(a.lo[k], b.lo[k]);
    n.hi[k] = std::max(a.hi[k], b.hi[k]);
  }
}

Scalar AabbTree::area(const Node& n) {
  const Scalar x = static_cast<Scalar>(n.hi[0]) - n.lo[0];
  const Scalar y = static_cast<Scalar>(n.hi[1]) - n.lo[1];
  const Scalar z = static_cast<Scalar>(n.hi[2]) - n.lo[2];
  return 2 * (x * y + y * z + z * x);
}

bool AabbTree::ray_hits_box(const Aabb& b, const Vec3& o, const Vec3& inv, Scalar s_max) {
  // Slab test. The box is widened by a relative allowance so that rounding in the divisions never
  // rejects a box the segment touches; an axis with a zero direction component has inv = +-inf
  // and is handled by the containment test of that axis.
  Scalar lo = 0;
  Scalar hi = s_max;
  for (int k = 0; k < 3; ++k) {
    const Scalar slack =
        tolerance::kArithmetic * (std::abs(b.min[k]) + std::abs(b.max[k]) + std::abs(o[k])) +
        tolerance::kFloor;
    const Scalar bmin = b.min[k] - slack;
    const Scalar bmax = b.max[k] + slack;
    if (std::isinf(inv[k])) {
      if (o[k] < bmin || o[k] > bmax) return false;
      continue;
    }
    Scalar t0 = (bmin - o[k]) * inv[k];
    Scalar t1 = (bmax - o[k]) * inv[k];
    if (t0 > t1) std::swap(t0, t1);
    // Relative widening of the parameter interval against rounding of the products.
    t0 -= tolerance::kArithmetic * std::abs(t0);
    t1 += tolerance::kArithmetic * std::abs(t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) return false;
  }
  return true;
}

std::int32_t AabbTree::allocate() {
  if (!free_.empty()) {
    const std::int32_t i = free_.back();
    free_.pop_back();
    nodes_[i] = Node{};
    parent_[i] = kNull;
    height_[i] = 0;
    return i;
  }
  nodes_.emplace_back();
  parent_.push_back(kNull);
  height_.push_back(0);
  return static_cast<std::int32_t>(nodes_.size() - 1);
}

void AabbTree::release(std::int32_t i) { free_.push_back(i); }

void AabbTree::insert(std::uint32_t object, const Aabb& box) {
  assert(!contains(object));
  if (leaf_of_.size() <= object) leaf_of_.resize(std::size_t{object} + 1, kNull);
  const std::int32_t leaf = allocate();
  set_node_box(nodes_[leaf], box);
  nodes_[leaf].child2 = static_cast<std::int32_t>(object);
  leaf_of_[object] = leaf;
  insert_leaf(leaf);
  ++leaves_;
  changed();
}

void AabbTree::remove(std::uint32_t object) {
  const std::int32_t leaf = leaf_of_[object];
  remove_leaf(leaf);
  release(leaf);
  leaf_of_[object] = kNull;
  --leaves_;
  changed();
}

void AabbTree::move(std::uint32_t object, const Aabb& box) {
  const std::int32_t leaf = leaf_of_[object];
  remove_leaf(leaf);
  set_node_box(nodes_[leaf], box);
  insert_leaf(leaf);
  changed();
}

void AabbTree::set_box(std::uint32_t object, const Aabb& box) {
  set_node_box(nodes_[leaf_of_[object]], box);
}

void AabbTree::changed() {
  constexpr std::size_t kMinChanges = 64;  // small trees: rebuilding costs more than it saves
  if (++changes_ >= std::max(kMinChanges, leaves_ / 2)) rebuild();
}

Scalar AabbTree::refit_subtree(std::int32_t i) {
  Node& n = nodes_[i];
  if (n.child1 == kNull) return 0;
  Scalar below1 = 0;
  Scalar below2 = 0;
  if (height_[i] > kParallelHeight) {  // disjoint subtrees: in parallel, same sums in any case
    parallel::invoke([&] { below1 = refit_subtree(n.child1); },
                     [&] { below2 = refit_subtree(n.child2); });
  } else {
    below1 = refit_subtree(n.child1);
    below2 = refit_subtree(n.child2);
  }
  merge_into(n, nodes_[n.child1], nodes_[n.child2]);
  return below1 + below2 + area(n);
}

void AabbTree::refit() {
  if (root_ == kNull) return;
  Scalar sum = 0;
  // One backward pass over the nodes in depth-first order (children after their parent), without
  // recursion, when they are in that order, or when no leaf was inserted or removed since the last
  // refit (then they are put in that order first, and likely stay so: a world whose objects only
  // move). A tree changed between refits (jumps reinserted every frame) is refitted recursively:
  // relaying it out costs more than the recursion saves. Tall trees: in parallel over subtrees.
  const bool linear = height_[root_] <= kParallelHeight && (ordered_ || stable_);
  stable_ = true;
  if (!linear) {
    sum = refit_subtree(root_);
  } else {
    if (!ordered_) relayout();
    for (std::size_t i = nodes_.size(); i-- > 0;) {
      Node& n = nodes_[i];
      if (n.child1 == kNull) continue;
      merge_into(n, nodes_[n.child1], nodes_[n.child2]);
      sum += area(n);
    }
  }
  const Scalar root_area = area(nodes_[root_]);
  // Loose: the boxes' total area (the expected cost of a query) grew by half since the rebuild.
  if (root_area > 0 && sum / root_area > 1.5 * built_area_ && leaves_ >= 64) rebuild();
}

namespace {

struct BuildItem {
  float centre[3];  // twice the box centre
  std::uint32_t object;
};

}  // namespace

void AabbTree::rebuild() {
  changes_ = 0;
  if (root_ == kNull) {
    built_area_ = 0;
    return;
  }
  std::vector<BuildItem> items;
  items.reserve(leaves_);
  for (std::size_t object = 0; object < leaf_of_.size(); ++object) {
    const std::int32_t leaf = leaf_of_[object];
    if (leaf == kNull) continue;
    const Node& n = nodes_[leaf];
    items.push_back({{n.lo[0] + n.hi[0], n.lo[1] + n.hi[1], n.lo[2] + n.hi[2]},
                     static_cast<std::uint32_t>(object)});
  }
  std::vector<Node> next(2 * items.size() - 1);
  parent_.assign(next.size(), kNull);
  height_.assign(next.size(), 0);
  free_.clear();
  // The subtree over items [first, last) at position `at` (depth-first order: the left subtree
  // follows at + 1, the right one after the left's 2m - 1 nodes), split at the median of the
  // centres along the axis where they spread most. Depth ceil(log2 n); recursion depth the same.
  const auto build = [&](auto&& self, BuildItem* first, BuildItem* last, std::int32_t at,
                         std::int32_t parent) -> void {
    parent_[at] = parent;
    const std::ptrdiff_t count = last - first;
    if (count == 1) {
      next[at] = nodes_[leaf_of_[first->object]];
      leaf_of_[first->object] = at;
      return;
    }
    float lo[3] = {first->centre[0], first->centre[1], first->centre[2]};
    float hi[3] = {lo[0], lo[1], lo[2]};
    for (const BuildItem* p = first + 1; p != last; ++p) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p->centre[k]);
        hi[k] = std::max(hi[k], p->centre[k]);
      }
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
      if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    }
    BuildItem* mid = first + count / 2;
    std::nth_element(first, mid, last, [axis](const BuildItem& a, const BuildItem& b) {
      // Ties by object: the same tree for the same input.
      return a.centre[axis] != b.centre[axis] ? a.centre[axis] < b.centre[axis]
                                              : a.object < b.object;
    });
    const auto left = at + 1;
    const auto right = at + 2 * static_cast<std::int32_t>(count / 2);
    if (count > kParallelBuild) {  // disjoint ranges and node positions: the same tree in parallel
      parallel::invoke([&] { self(self, first, mid, left, at); },
                       [&] { self(self, mid, last, right, at); });
    } else {
      self(self, first, mid, left, at);
      self(self, mid, last, right, at);
    }
    Node& n = next[at];
    n.child1 = left;
    n.child2 = right;
    merge_into(n, next[left], next[right]);
    height_[at] = 1 + std::max(height_[left], height_[right]);
  };
  build(build, items.data(), items.data() + items.size(), 0, kNull);
  nodes_ = std::move(next);
  root_ = 0;
  ordered_ = true;
  built_area_ = relative_area();
}

void AabbTree::relayout() {
  struct Item {
    std::int32_t old;     // the node's index before
    std::int32_t parent;  // its parent's index after (kNull for the root)
    bool second;          // whether it is that parent's child2
  };
  std::vector<Node> next(2 * leaves_ - 1);
  std::vector<std::int32_t> parent(next.size(), kNull);
  std::vector<std::int32_t> height(next.size(), 0);
  std::int32_t at = 0;
  Stack<Item> stack;
  stack.push({root_, kNull, false});
  while (!stack.empty()) {
    const Item item = stack.pop();
    const Node& n = nodes_[item.old];
    next[at] = n;
    parent[at] = item.parent;
    height[at] = height_[item.old];
    if (item.parent != kNull)
      (item.second ? next[item.parent].child2 : next[item.parent].child1) = at;
    if (n.child1 == kNull) {
      leaf_of_[n.child2] = at;
    } else {
      stack.push({n.child2, at, true});  // popped after the whole child1 subtree
      stack.push({n.child1, at, false});
    }
    ++at;
  }
  nodes_ = std::move(next);
  parent_ = std::move(parent);
  height_ = std::move(height);
  free_.clear();
  root_ = 0;
  ordered_ = true;
}

Scalar AabbTree::relative_area() const {
  if (root_ == kNull || nodes_[root_].child1 == kNull) return 0;
  Scalar sum = 0;
  Stack<std::int32_t> stack;
  stack.push(root_);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.pop()];
    if (n.child1 == kNull) continue;
    sum += area(n);
    stack.push(n.child1);
    stack.push(n.child2);
  }
  const Scalar root_area = area(nodes_[root_]);
  return root_area > 0 ? sum / root_area : 0;
}

std::vector<AabbTree::PairTask> AabbTree::pair_tasks(Scalar gap, std::size_t target) const {
  std::vector<PairTask> tasks;
  if (root_ == kNull) return tasks;
  tasks.push_back(all_pairs());
  // Expand every task one level per round (a subtree into its two subtrees and their cross pairs,
  // a cross pair into the two halves of its larger side), dropping cross pairs that are too far
  // apart, until there are enough tasks or nothing is left to expand.
  std::vector<PairTask> next;
  for (int round = 0; round < 24 && tasks.size() < target; ++round) {
    next.clear();
    bool expanded = false;
    for (const PairTask t : tasks) {
      const Node& a = nodes_[t.a];
      const Node& b = nodes_[t.b];
      if (t.a == t.b) {
        if (a.child1 == kNull) continue;  // one leaf: no pairs
        next.push_back({a.child1, a.child1});
        next.push_back({a.child2, a.child2});
        next.push_back({a.child1, a.child2});
        expanded = true;
        continue;
      }
      if (!near(a, b, gap)) continue;
      const bool a_leaf = a.child1 == kNull;
      const bool b_leaf = b.child1 == kNull;
      if (a_leaf && b_leaf) {
        next.push_back(t);
      } else if (b_leaf || (!a_leaf && span(a) >= span(b))) {
        next.push_back({a.child1, t.b});
        next.push_back({a.child2, t.b});
        expanded = true;
      } else {
        next.push_back({t.a, b.child1});
        next.push_back({t.a, b.child2});
        expanded = true;
      }
    }
    tasks.swap(next);
    if (!expanded) break;
  }
  return tasks;
}

void AabbTree::insert_leaf(std::int32_t leaf) {
  ordered_ = false;
  stable_ = false;
  if (root_ == kNull) {
    root_ = leaf;
    parent_[leaf] = kNull;
    return;
  }
  Node box = nodes_[leaf];
  std::int32_t index = root_;
  while (nodes_[index].child1 != kNull) {
    const Node& n = nodes_[index];
    Node m;
    merge_into(m, n, box);
    const Scalar here = area(n);
    const Scalar combined = area(m);
    // Cost of making the leaf this node's sibling, and the minimum cost pushed down to children.
    const Scalar sibling_cost = 2 * combined;
    const Scalar inherited = 2 * (combined - here);
    const auto child_cost = [&](std::int32_t c) {
      Node mc;
      merge_into(mc, nodes_[c], box);
      if (nodes_[c].child1 == kNull) return area(mc) + inherited;
      return area(mc) - area(nodes_[c]) + inherited;
    };
    const Scalar cost1 = child_cost(n.child1);
    const Scalar cost2 = child_cost(n.child2);
    if (sibling_cost < cost1 && sibling_cost < cost2) break;
    index = cost1 <= cost2 ? n.child1 : n.child2;
  }
  const std::int32_t sibling = index;
  const std::int32_t old_parent = parent_[sibling];
  const std::int32_t parent = allocate();  // may reallocate nodes_: no references held here
  parent_[parent] = old_parent;
  merge_into(nodes_[parent], box, nodes_[sibling]);
  height_[parent] = height_[sibling] + 1;
  nodes_[parent].child1 = sibling;
  nodes_[parent].child2 = leaf;
  parent_[sibling] = parent;
  parent_[leaf] = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  refit_upwards(parent_[leaf]);
}

void AabbTree::remove_leaf(std::int32_t leaf) {
  ordered_ = false;
  stable_ = false;
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const std::int32_t parent = parent_[leaf];
  const std::int32_t grand = parent_[parent];
  const std::int32_t sibling =
      nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grand == kNull) {
    root_ = sibling;
    parent_[sibling] = kNull;
  } else {
    if (nodes_[grand].child1 == parent) {
      nodes_[grand].child1 = sibling;
    } else {
      nodes_[grand].child2 = sibling;
    }
    parent_[sibling] = grand;
    refit_upwards(grand);
  }
  release(parent);
  parent_[leaf] = kNull;
}

void AabbTree::refit_upwards(std::int32_t i) {
  while (i != kNull) {
    i = balance(i);
    Node& n = nodes_[i];
    height_[i] = 1 + std::max(height_[n.child1], height_[n.child2]);
    merge_into(n, nodes_[n.child1], nodes_[n.child2]);
    i = parent_[i];
  }
}

// If one child of `a` is more than one level taller than the other, lifts that child into a's
// place and hands one of its own children down to `a`: the taller grandchild stays with the lifted
// node. Returns the index now at a's position.
std::int32_t AabbTree::balance(std::int32_t a) {
  Node& na = nodes_[a];
  if (na.child1 == kNull || height_[a] < 2) return a;
  const std::int32_t b = na.child1;
  const std::int32_t c = na.child2;
  const std::int32_t diff = height_[c] - height_[b];
  if (diff >= -1 && diff <= 1) return a;
  // `up` is the taller child, `other` the shorter one.
  const std::int32_t up = diff > 1 ? c : b;
  const std::int32_t other = diff > 1 ? b : c;
  Node& nu = nodes_[up];
  const std::int32_t f = nu.child1;
  const std::int32_t g = nu.child2;
  // Lift `up` into a's place.
  nu.child1 = a;
  parent_[up] = parent_[a];
  parent_[a] = up;
  if (parent_[up] == kNull) {
    root_ = up;
  } else if (nodes_[parent_[up]].child1 == a) {
    nodes_[parent_[up]].child1 = up;
  } else {
    nodes_[parent_[up]].child2 = up;
  }
  // The taller of up's children stays under up; the shorter goes down to a.
  const bool keep_f = height_[f] > height_[g];
  const std::int32_t keep = keep_f ? f : g;
  const std::int32_t give = keep_f ? g : f;
  nu.child2 = keep;
  na.child1 = other;
  na.child2 = give;
  parent_[give] = a;
  merge_into(na, nodes_[other], nodes_[give]);
  height_[a] = 1 + std::max(height_[other], height_[give]);
  merge_into(nu, na, nodes_[keep]);
  height_[up] = 1 + std::max(height_[a], height_[keep]);
  return up;
}

}  // namespace antcd::detail
