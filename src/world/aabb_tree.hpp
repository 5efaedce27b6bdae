// Private: the World's broad phase, a dynamic AABB tree (a binary tree of axis-aligned boxes whose
// leaves are objects) kept balanced by AVL-style rotations, with insertion guided by the growth of
// surface area. Leaves hold fattened boxes so that small motions need no update (docs/design.md).
//
// Layout: 32-byte nodes (single-precision boxes rounded outward, so a node box always contains the
// double box it was made from; two children or one object), with parents and heights kept apart
// because only the mutations read them. A leaf is addressed by its object (a small integer, the
// World's slot), so a rebuild (or the relayout before a refit) may renumber every node: it lays the
// tree out in depth-first order, which keeps a subtree in one stretch of memory for the traversals.
//
// Keeping it tight: greedy insertion and height-only rotations keep the height O(log n) but not the
// boxes tight (on many objects spread through a volume, internal boxes grow into overlapping
// slabs). So after as many incremental changes as half the leaves, the tree is rebuilt top-down
// (median splits along the widest axis of the leaves' centres): amortized O(log n) per change. A
// frame in which many objects leave their fattened boxes instead replaces their leaf boxes and
// refits every internal box in one O(n) pass (set_box + refit); refit rebuilds when the surface
// area of the internal boxes has grown by half over what the last rebuild produced.
#pragma once

#include <antcd/math.hpp>

#include "util/portable.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace antcd::detail {

inline bool boxes_overlap(const Aabb& a, const Aabb& b) {
  return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() &&
         b.min.y() <= a.max.y() && a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}

inline bool box_contains(const Aabb& outer, const Aabb& inner) {
  return (outer.min.array() <= inner.min.array()).all() &&
         (inner.max.array() <= outer.max.array()).all();
}

class AabbTree {
 public:
  static constexpr std::int32_t kNull = -1;

  /// A unit of the all-pairs traversal: every pair within subtree `a` (a == b), or every pair with
  /// one leaf under `a` and one under `b`. Independent of each other: run them on any threads.
  struct PairTask {
    std::int32_t a;
    std::int32_t b;
  };

  /// Adds a leaf with `box` for `object` (not yet in the tree). O(log n).
  void insert(std::uint32_t object, const Aabb& box);
  void remove(std::uint32_t object);
  /// Replaces a leaf's box by a removal and an insertion. O(log n).
  void move(std::uint32_t object, const Aabb& box);
  /// Replaces a leaf's box without touching its ancestors: after a batch of these, call refit()
  /// before any other member function.
  void set_box(std::uint32_t object, const Aabb& box);
  /// Recomputes every internal box from its children (O(n)); rebuilds when the tree got loose.
  void refit();

  [[nodiscard]] bool contains(std::uint32_t object) const {
    return object < leaf_of_.size() && leaf_of_[object] != kNull;
  }
  /// The box stored for `object` (its box rounded outward to single precision).
  [[nodiscard]] Aabb box(std::uint32_t object) const { return to_aabb(nodes_[leaf_of_[object]]); }
  /// Whether `box` lies inside the box of the leaf's ancestor `levels` above it (the root's box
  /// when the leaf is not that deep): refitting the leaf to `box` then grows no box above that
  /// ancestor. Reads only internal nodes: safe beside set_box() calls on other leaves.
  [[nodiscard]] bool inside_ancestor(std::uint32_t object, const Aabb& box, int levels) const {
    std::int32_t i = leaf_of_[object];
    for (int k = 0; k < levels && parent_[i] != kNull; ++k) i = parent_[i];
    const Node& n = nodes_[i];
    for (int k = 0; k < 3; ++k) {
      if (box.min[k] < static_cast<Scalar>(n.lo[k]) || static_cast<Scalar>(n.hi[k]) < box.max[k]) {
        return false;
      }
    }
    return true;
  }
  /// Starts loading the leaf of `object` (if any), for a later box() or set_box().
  void prefetch(std::uint32_t object) const {
    if (object < leaf_of_.size() && leaf_of_[object] != kNull) {
      ANTCD_PREFETCH_WRITE(&nodes_[leaf_of_[object]]);
    }
  }
  [[nodiscard]] std::size_t size() const { return leaves_; }
  [[nodiscard]] std::size_t memory_bytes() const {
    return nodes_.capacity() * sizeof(Node) +
           (parent_.capacity() + height_.capacity() + free_.capacity() + leaf_of_.capacity()) *
               sizeof(std::int32_t);
  }
  [[nodiscard]] std::int32_t height() const { return root_ == kNull ? 0 : height_[root_]; }
  /// Rebuilds the whole tree top-down (objects keep their boxes).
  void rebuild();
  /// Total surface area of the internal nodes' boxes divided by the root's: the expected number of
  /// internal nodes a small random query box inside the root visits (the SAH cost; tree quality).
  [[nodiscard]] Scalar relative_area() const;

  // Read-only node access for traversals outside this class (world/nearest.cpp): node indices
  // from root() (kNull: empty tree) down through child(node, 0 or 1); a leaf's object is object().
  [[nodiscard]] std::int32_t root() const { return root_; }
  [[nodiscard]] bool is_leaf(std::int32_t node) const { return nodes_[node].child1 == kNull; }
  [[nodiscard]] std::int32_t child(std::int32_t node, int k) const {
    return k == 0 ? nodes_[node].child1 : nodes_[node].child2;
  }
  [[nodiscard]] std::uint32_t object(std::int32_t leaf) const {
    return static_cast<std::uint32_t>(nodes_[leaf].child2);
  }
  [[nodiscard]] Aabb node_box(std::int32_t node) const { return to_aabb(nodes_[node]); }

  /// Calls visit(object) for every leaf whose box overlaps `box`. Reentrant (read only).
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const {
    if (root_ == kNull) return;
    Stack<std::int32_t> stack;
    stack.push(root_);
    while (!stack.empty()) {
      const Node& n = nodes_[stack.pop()];
      if (!overlaps(n, box)) continue;
      if (n.child1 == kNull) {
        visit(static_cast<std::uint32_t>(n.child2));
        continue;
      }
      stack.push(n.child1);
      stack.push(n.child2);
    }
  }

  /// Calls visit(object) for every leaf whose box the segment origin + s * dir, s in [0, *s_max],
  /// meets; visit may lower *s_max to prune farther boxes. `inv_dir` holds 1 / dir per axis.
  template <class Visit>
  void ray_query(const Vec3& origin, const Vec3& inv_dir, const Scalar* s_max,
                 Visit&& visit) const {
    if (root_ == kNull) return;
    Stack<std::int32_t> stack;
    stack.push(root_);
    while (!stack.empty()) {
      const Node& n = nodes_[stack.pop()];
      if (!ray_hits_box(to_aabb(n), origin, inv_dir, *s_max)) continue;
      if (n.child1 == kNull) {
        visit(static_cast<std::uint32_t>(n.child2));
        continue;
      }
      stack.push(n.child1);
      stack.push(n.child2);
    }
  }

  /// Slab test, conservative: a box the segment touches is never rejected.
  static bool ray_hits_box(const Aabb& b, const Vec3& o, const Vec3& inv, Scalar s_max);

  /// Splits the all-pairs traversal at `gap` into about `target` independent tasks (fewer on a
  /// small tree), in an order that depends only on the tree.
  [[nodiscard]] std::vector<PairTask> pair_tasks(Scalar gap, std::size_t target) const;

  /// Calls visit(object_a, object_b) once for every unordered pair of distinct leaves under `task`
  /// whose boxes are within `gap` of each other on every axis (a's box grown by gap overlaps b's).
  /// Reentrant (read only).
  template <class Visit>
  void pairs(PairTask task, Scalar gap, Visit&& visit) const {
    // A tree that fits the first-level caches gains nothing from prefetching, which costs about a
    // fifth of the traversal's instructions (the production line's 90 objects: 179 nodes).
    const bool prefetch = nodes_.size() > kPrefetchNodes;
    if (gap == 0) {
      prefetch ? pairs_within<true, true>(task, gap, visit)
               : pairs_within<true, false>(task, gap, visit);
    } else {
      prefetch ? pairs_within<false, true>(task, gap, visit)
               : pairs_within<false, false>(task, gap, visit);
    }
  }
  /// The whole traversal as one task.
  [[nodiscard]] PairTask all_pairs() const { return {root_, root_}; }

 private:
  struct Node {
    float lo[3];
    float hi[3];
    std::int32_t child1 = kNull;  // kNull for a leaf
    std::int32_t child2 = kNull;  // a leaf: its object
  };

  /// Trees of up to this many nodes (32 bytes each) are traversed without prefetching.
  static constexpr std::size_t kPrefetchNodes = 512;

  /// pairs(), with the box test specialized for a zero gap (the usual case: exact contact), and
  /// with or without prefetching.
  template <bool kZeroGap, bool kPrefetch, class Visit>
  void pairs_within(PairTask task, Scalar gap, Visit& visit) const {
    const auto near = [gap](const Node& a, const Node& b) {
      return kZeroGap ? touch(a, b) : AabbTree::near(a, b, gap);
    };
    if (task.a == kNull) return;
    if (task.a != task.b && !near(nodes_[task.a], nodes_[task.b])) return;
    // Every entry on the stack is a subtree (a == b) or a pair of nodes already found near: the
    // children are tested before they are pushed, while their parent's cache line is warm.
    // Pushing an entry starts loading the children it will read when popped (the traversal waits
    // on memory: a large world's tree does not fit the caches).
    Stack<PairTask> stack;
    push_pair<kPrefetch>(stack, task.a, task.b);
    while (!stack.empty()) {
      const PairTask t = stack.pop();
      const Node& a = nodes_[t.a];
      if (t.a == t.b) {  // pairs within one subtree
        if (a.child1 == kNull) continue;
        if (nodes_[a.child1].child1 != kNull) push_pair<kPrefetch>(stack, a.child1, a.child1);
        if (nodes_[a.child2].child1 != kNull) push_pair<kPrefetch>(stack, a.child2, a.child2);
        if (near(nodes_[a.child1], nodes_[a.child2]))
          push_pair<kPrefetch>(stack, a.child1, a.child2);
        continue;
      }
      const Node& b = nodes_[t.b];
      const bool a_leaf = a.child1 == kNull;
      const bool b_leaf = b.child1 == kNull;
      if (a_leaf && b_leaf) {
        visit(static_cast<std::uint32_t>(a.child2), static_cast<std::uint32_t>(b.child2));
      } else if (b_leaf || (!a_leaf && span(a) >= span(b))) {
        if (near(nodes_[a.child1], b)) push_pair<kPrefetch>(stack, a.child1, t.b);
        if (near(nodes_[a.child2], b)) push_pair<kPrefetch>(stack, a.child2, t.b);
      } else {
        if (near(a, nodes_[b.child1])) push_pair<kPrefetch>(stack, t.a, b.child1);
        if (near(a, nodes_[b.child2])) push_pair<kPrefetch>(stack, t.a, b.child2);
      }
    }
  }

  /// Pushes the pair (a, b) of pairs_within() and starts loading the children it will read when
  /// popped. Inlined by force: called for every node pair the traversal keeps.
  template <bool kPrefetch, class S>
  [[gnu::always_inline]] void push_pair(S& stack, std::int32_t a, std::int32_t b) const {
    stack.push({a, b});
    if (!kPrefetch) return;
    for (const std::int32_t i : {a, b}) {
      const Node& n = nodes_[i];
      if (n.child1 != kNull) {
        ANTCD_PREFETCH(&nodes_[n.child1]);
        ANTCD_PREFETCH(&nodes_[n.child2]);
      }
      if (a == b) break;
    }
  }

  /// A traversal stack: on the call stack up to 256 entries, then on the heap (degenerate trees).
  template <class T>
  class Stack {
   public:
    [[gnu::always_inline]] void push(T v) {
      if (top_ < kInline) {
        inline_[top_++] = v;
      } else {
        spill_.push_back(v);
      }
    }
    // The heap holds entries only while the inline array is full, so a stack with room inline
    // never looks at it.
    [[gnu::always_inline]] T pop() {
      if (top_ == kInline && !spill_.empty()) {
        const T v = spill_.back();
        spill_.pop_back();
        return v;
      }
      return inline_[--top_];
    }
    [[nodiscard]] bool empty() const { return top_ == 0; }

   private:
    static constexpr int kInline = 256;
    T inline_[kInline];
    int top_ = 0;
    std::vector<T> spill_;
  };

  static Aabb to_aabb(const Node& n) {
    Aabb b;
    b.min = Vec3(n.lo[0], n.lo[1], n.lo[2]);
    b.max = Vec3(n.hi[0], n.hi[1], n.hi[2]);
    return b;
  }
  static void set_node_box(Node& n, const Aabb& b);
  static void merge_into(Node& n, const Node& a, const Node& b);
  static bool overlaps(const Node& n, const Aabb& b) {
    for (int k = 0; k < 3; ++k) {
      if (static_cast<Scalar>(n.lo[k]) > b.max[k] || b.min[k] > static_cast<Scalar>(n.hi[k])) {
        return false;
      }
    }
    return true;
  }
  /// Whether two node boxes overlap (touching counts), without branches: the six comparisons of
  /// near() at gap 0, four lanes at a time (the fourth lane, which reads past a box, is ignored).
  [[gnu::always_inline]] static bool touch(const Node& a, const Node& b) {
#if defined(__SSE2__)
    const __m128 ok = _mm_and_ps(_mm_cmple_ps(_mm_loadu_ps(a.lo), _mm_loadu_ps(b.hi)),
                                 _mm_cmple_ps(_mm_loadu_ps(b.lo), _mm_loadu_ps(a.hi)));
    return (_mm_movemask_ps(ok) & 7) == 7;
#else
    return near(a, b, 0);
#endif
  }
  [[gnu::always_inline]] static bool near(const Node& a, const Node& b, Scalar gap) {
    if (gap == 0) {  // exact in single precision
      return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
             a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
    }
    for (int k = 0; k < 3; ++k) {
      if (static_cast<Scalar>(a.lo[k]) - gap > static_cast<Scalar>(b.hi[k]) ||
          static_cast<Scalar>(b.lo[k]) - gap > static_cast<Scalar>(a.hi[k])) {
        return false;
      }
    }
    return true;
  }
  static float span(const Node& n) {
    return (n.hi[0] - n.lo[0]) + (n.hi[1] - n.lo[1]) + (n.hi[2] - n.lo[2]);
  }
  static Scalar area(const Node& n);

  std::int32_t allocate();
  void release(std::int32_t i);
  /// Counts an incremental change; rebuilds after enough of them (see the header comment).
  void changed();
  void insert_leaf(std::int32_t leaf);
  void remove_leaf(std::int32_t leaf);
  std::int32_t balance(std::int32_t a);
  void refit_upwards(std::int32_t i);
  /// Renumbers the nodes in depth-first order (the tree unchanged): a parent before its children.
  void relayout();
  /// Refits the subtree at i; returns the sum of its internal nodes' areas.
  Scalar refit_subtree(std::int32_t i);

  // Subtrees taller than this are refitted, and ranges longer than this built, by two oneTBB tasks.
  static constexpr std::int32_t kParallelHeight = 12;
  static constexpr std::ptrdiff_t kParallelBuild = 8192;

  std::vector<Node> nodes_;
  std::vector<std::int32_t> parent_;
  std::vector<std::int32_t> height_;  // leaf 0
  std::vector<std::int32_t> free_;
  std::vector<std::int32_t> leaf_of_;  // by object; kNull when absent
  std::int32_t root_ = kNull;
  std::size_t leaves_ = 0;
  std::size_t changes_ = 0;  // incremental changes since the last rebuild
  bool ordered_ = false;     // nodes_ in depth-first order, none free (rebuild, relayout)
  bool stable_ = false;      // no leaf inserted or removed since the last refit
  Scalar built_area_ = 0;    // relative_area() right after the last rebuild
};

}  // namespace antcd::detail
