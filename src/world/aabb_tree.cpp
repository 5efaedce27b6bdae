// The dynamic AABB tree of the World's broad phase (see aabb_tree.hpp).
//
// Insertion walks down from the root choosing, at each internal node, between making the new leaf
// a sibling of that node and descending into one of its children, by the increase of surface area
// each choice causes (the usual cost model of bounding-volume trees: the chance that a random query
// box overlaps a node grows with its area). On the way back up, nodes whose children's heights
// differ by more than one are rotated (as in an AVL tree), so the height stays O(log n) whatever
// the insertion order. Every n/2 changes the tree is rebuilt top-down (aabb_tree.hpp says why).
#include "world/aabb_tree.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

namespace antcd::detail {

namespace {

Aabb merged(const Aabb& a, const Aabb& b) {
  Aabb out;
  out.min = a.min.cwiseMin(b.min);
  out.max = a.max.cwiseMax(b.max);
  return out;
}

Scalar area(const Aabb& b) {
  const Vec3 e = b.max - b.min;
  return 2 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
}

}  // namespace

bool AabbTree::ray_hits_box(const Aabb& b, const Vec3& o, const Vec3& inv, Scalar s_max) {
  // Slab test. The box is widened by a relative allowance so that rounding in the divisions never
  // rejects a box the segment touches; an axis with a zero direction component has inv = +-inf
  // and is handled by the containment test of that axis.
  Scalar lo = 0;
  Scalar hi = s_max;
  for (int k = 0; k < 3; ++k) {
    const Scalar slack = 1e-12 * (std::abs(b.min[k]) + std::abs(b.max[k]) + std::abs(o[k])) +
                         1e-300;
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
    t0 -= 1e-12 * std::abs(t0);
    t1 += 1e-12 * std::abs(t1);
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
    return i;
  }
  nodes_.emplace_back();
  return static_cast<std::int32_t>(nodes_.size() - 1);
}

void AabbTree::release(std::int32_t i) { free_.push_back(i); }

std::int32_t AabbTree::insert(const Aabb& box, std::uint32_t object) {
  const std::int32_t leaf = allocate();
  nodes_[leaf].box = box;
  nodes_[leaf].object = object;
  insert_leaf(leaf);
  ++leaves_;
  changed();
  return leaf;
}

void AabbTree::remove(std::int32_t leaf) {
  remove_leaf(leaf);
  release(leaf);
  --leaves_;
  changed();
}

void AabbTree::move(std::int32_t leaf, const Aabb& box) {
  remove_leaf(leaf);
  nodes_[leaf].box = box;
  insert_leaf(leaf);
  changed();
}

void AabbTree::changed() {
  constexpr std::size_t kMinChanges = 64;  // small trees: rebuilding costs more than it saves
  if (++changes_ >= std::max(kMinChanges, leaves_ / 2)) rebuild();
}

void AabbTree::rebuild() {
  changes_ = 0;
  if (root_ == kNull) return;
  std::vector<std::int32_t> leaves;
  leaves.reserve(leaves_);
  std::vector<std::int32_t> stack{root_};
  while (!stack.empty()) {
    const std::int32_t i = stack.back();
    stack.pop_back();
    if (nodes_[i].child1 == kNull) {
      leaves.push_back(i);
      continue;
    }
    stack.push_back(nodes_[i].child1);
    stack.push_back(nodes_[i].child2);
    release(i);
  }
  root_ = build(leaves.data(), leaves.data() + leaves.size());
  nodes_[root_].parent = kNull;
}

// The subtree over leaves [first, last): split at the median of the leaves' centres along the axis
// where those centres spread most. Depth ceil(log2 n); recursion depth the same.
std::int32_t AabbTree::build(std::int32_t* first, std::int32_t* last) {
  const std::ptrdiff_t count = last - first;
  if (count == 1) return *first;
  Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
  Vec3 hi = -lo;
  for (const std::int32_t* p = first; p != last; ++p) {
    const Vec3 c = nodes_[*p].box.min + nodes_[*p].box.max;  // twice the centre
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::int32_t* mid = first + count / 2;
  std::nth_element(first, mid, last, [&](std::int32_t a, std::int32_t b) {
    const Scalar ca = nodes_[a].box.min[axis] + nodes_[a].box.max[axis];
    const Scalar cb = nodes_[b].box.min[axis] + nodes_[b].box.max[axis];
    return ca != cb ? ca < cb : a < b;  // ties by index: the same tree for the same input
  });
  const std::int32_t child1 = build(first, mid);
  const std::int32_t child2 = build(mid, last);
  const std::int32_t parent = allocate();
  Node& n = nodes_[parent];
  n.child1 = child1;
  n.child2 = child2;
  n.box = merged(nodes_[child1].box, nodes_[child2].box);
  n.height = 1 + std::max(nodes_[child1].height, nodes_[child2].height);
  nodes_[child1].parent = parent;
  nodes_[child2].parent = parent;
  return parent;
}

Scalar AabbTree::relative_area() const {
  if (root_ == kNull || nodes_[root_].child1 == kNull) return 0;
  Scalar sum = 0;
  std::vector<std::int32_t> stack{root_};
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (n.child1 == kNull) continue;
    sum += area(n.box);
    stack.push_back(n.child1);
    stack.push_back(n.child2);
  }
  return sum / area(nodes_[root_].box);
}

void AabbTree::insert_leaf(std::int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  const Aabb box = nodes_[leaf].box;
  std::int32_t index = root_;
  while (nodes_[index].child1 != kNull) {
    const Node& n = nodes_[index];
    const Scalar here = area(n.box);
    const Scalar combined = area(merged(n.box, box));
    // Cost of making the leaf this node's sibling, and the minimum cost pushed down to children.
    const Scalar sibling_cost = 2 * combined;
    const Scalar inherited = 2 * (combined - here);
    const auto child_cost = [&](std::int32_t c) {
      const Aabb m = merged(nodes_[c].box, box);
      if (nodes_[c].child1 == kNull) return area(m) + inherited;
      return area(m) - area(nodes_[c].box) + inherited;
    };
    const Scalar cost1 = child_cost(n.child1);
    const Scalar cost2 = child_cost(n.child2);
    if (sibling_cost < cost1 && sibling_cost < cost2) break;
    index = cost1 <= cost2 ? n.child1 : n.child2;
  }
  const std::int32_t sibling = index;
  const std::int32_t old_parent = nodes_[sibling].parent;
  const std::int32_t parent = allocate();
  nodes_[parent].parent = old_parent;
  nodes_[parent].box = merged(box, nodes_[sibling].box);
  nodes_[parent].height = nodes_[sibling].height + 1;
  nodes_[parent].child1 = sibling;
  nodes_[parent].child2 = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  refit_upwards(nodes_[leaf].parent);
}

void AabbTree::remove_leaf(std::int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t grand = nodes_[parent].parent;
  const std::int32_t sibling =
      nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grand == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
  } else {
    if (nodes_[grand].child1 == parent) {
      nodes_[grand].child1 = sibling;
    } else {
      nodes_[grand].child2 = sibling;
    }
    nodes_[sibling].parent = grand;
    refit_upwards(grand);
  }
  release(parent);
  nodes_[leaf].parent = kNull;
}

void AabbTree::refit_upwards(std::int32_t i) {
  while (i != kNull) {
    i = balance(i);
    Node& n = nodes_[i];
    n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
    n.box = merged(nodes_[n.child1].box, nodes_[n.child2].box);
    i = n.parent;
  }
}

// If one child of `a` is more than one level taller than the other, lifts that child into a's
// place and hands one of its own children down to `a`: the taller grandchild stays with the lifted
// node. Returns the index now at a's position.
std::int32_t AabbTree::balance(std::int32_t a) {
  Node& na = nodes_[a];
  if (na.child1 == kNull || na.height < 2) return a;
  const std::int32_t b = na.child1;
  const std::int32_t c = na.child2;
  const std::int32_t diff = nodes_[c].height - nodes_[b].height;
  if (diff >= -1 && diff <= 1) return a;
  // `up` is the taller child, `other` the shorter one.
  const std::int32_t up = diff > 1 ? c : b;
  const std::int32_t other = diff > 1 ? b : c;
  Node& nu = nodes_[up];
  const std::int32_t f = nu.child1;
  const std::int32_t g = nu.child2;
  // Lift `up` into a's place.
  nu.child1 = a;
  nu.parent = na.parent;
  na.parent = up;
  if (nu.parent == kNull) {
    root_ = up;
  } else if (nodes_[nu.parent].child1 == a) {
    nodes_[nu.parent].child1 = up;
  } else {
    nodes_[nu.parent].child2 = up;
  }
  // The taller of up's children stays under up; the shorter goes down to a.
  const bool keep_f = nodes_[f].height > nodes_[g].height;
  const std::int32_t keep = keep_f ? f : g;
  const std::int32_t give = keep_f ? g : f;
  nu.child2 = keep;
  na.child1 = other;
  na.child2 = give;
  nodes_[give].parent = a;
  na.box = merged(nodes_[other].box, nodes_[give].box);
  na.height = 1 + std::max(nodes_[other].height, nodes_[give].height);
  nu.box = merged(na.box, nodes_[keep].box);
  nu.height = 1 + std::max(na.height, nodes_[keep].height);
  return up;
}

}  // namespace antcd::detail
