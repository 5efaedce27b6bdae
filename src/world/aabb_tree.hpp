// Private: the World's broad phase, a dynamic AABB tree (a binary tree of axis-aligned boxes whose
// leaves are objects) kept balanced by AVL-style rotations, with insertion guided by the growth of
// surface area. Leaves hold fattened boxes so that small motions need no update (docs/design.md).
// Greedy insertion and height-only rotations keep the height O(log n) but not the boxes tight: on
// many objects spread through a volume, internal boxes grow into overlapping slabs and a query
// visits a large fraction of the tree. So after as many changes (insertions, removals, moves) as
// half the leaves, the tree is rebuilt top-down (median splits along the widest axis of the
// leaves' centres): O(n log n) every n/2 changes, amortized O(log n) per change.
#pragma once

#include <antcd/math.hpp>

#include <cstdint>
#include <vector>

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

  /// Inserts a leaf with `box` for `object`; returns the leaf's node index (stable until removed).
  std::int32_t insert(const Aabb& box, std::uint32_t object);
  void remove(std::int32_t leaf);
  /// Replaces a leaf's box (remove + insert of the same node index).
  void move(std::int32_t leaf, const Aabb& box);

  [[nodiscard]] const Aabb& box(std::int32_t leaf) const { return nodes_[leaf].box; }
  [[nodiscard]] std::size_t memory_bytes() const {
    return nodes_.capacity() * sizeof(Node) + free_.capacity() * sizeof(std::int32_t);
  }
  [[nodiscard]] std::int32_t height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
  /// Rebuilds the internal nodes top-down; leaf indices and boxes are unchanged.
  void rebuild();
  /// Total surface area of the internal nodes' boxes divided by the root's: the expected number of
  /// internal nodes a small random query box inside the root visits (the SAH cost; tree quality).
  [[nodiscard]] Scalar relative_area() const;

  /// Calls visit(object) for every leaf whose box overlaps `box`. Reentrant (read only).
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) const {
    if (root_ == kNull) return;
    std::int32_t stack[128];
    std::vector<std::int32_t> overflow;  // only for degenerate trees taller than the stack
    int top = 0;
    stack[top++] = root_;
    while (top > 0 || !overflow.empty()) {
      std::int32_t i;
      if (!overflow.empty()) {
        i = overflow.back();
        overflow.pop_back();
      } else {
        i = stack[--top];
      }
      const Node& n = nodes_[i];
      if (!boxes_overlap(n.box, box)) continue;
      if (n.child1 == kNull) {
        visit(n.object);
        continue;
      }
      for (const std::int32_t c : {n.child1, n.child2}) {
        if (top < 128) {
          stack[top++] = c;
        } else {
          overflow.push_back(c);
        }
      }
    }
  }

  /// Calls visit(object) for every leaf whose box the segment origin + s * dir, s in [0, *s_max],
  /// meets; visit may lower *s_max to prune farther boxes. `inv_dir` holds 1 / dir per axis.
  template <class Visit>
  void ray_query(const Vec3& origin, const Vec3& inv_dir, const Scalar* s_max,
                 Visit&& visit) const {
    if (root_ == kNull) return;
    std::vector<std::int32_t> stack{root_};
    while (!stack.empty()) {
      const std::int32_t i = stack.back();
      stack.pop_back();
      const Node& n = nodes_[i];
      if (!ray_hits_box(n.box, origin, inv_dir, *s_max)) continue;
      if (n.child1 == kNull) {
        visit(n.object);
        continue;
      }
      stack.push_back(n.child1);
      stack.push_back(n.child2);
    }
  }

  /// Slab test, conservative: a box the segment touches is never rejected.
  static bool ray_hits_box(const Aabb& b, const Vec3& o, const Vec3& inv, Scalar s_max);

 private:
  struct Node {
    Aabb box;
    std::int32_t parent = kNull;
    std::int32_t child1 = kNull;  // kNull for a leaf
    std::int32_t child2 = kNull;
    std::int32_t height = 0;  // leaf 0
    std::uint32_t object = 0;
  };

  std::int32_t allocate();
  std::int32_t build(std::int32_t* first, std::int32_t* last);
  /// Counts a change; rebuilds after enough of them (see the header comment).
  void changed();
  void release(std::int32_t i);
  void insert_leaf(std::int32_t leaf);
  void remove_leaf(std::int32_t leaf);
  std::int32_t balance(std::int32_t a);
  void refit_upwards(std::int32_t i);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> free_;
  std::int32_t root_ = kNull;
  std::size_t leaves_ = 0;
  std::size_t changes_ = 0;  // since the last rebuild
};

}  // namespace antcd::detail
