// Private: the depth-first dual traversal shared by every narrow phase.
#pragma once

#include <antcd/bvh.hpp>

#include <array>
#include <cassert>

namespace antcd::detail {

/// Relative placement of model B in model A's frame plus the culling margin.
struct PairFrame {
  Transform b_to_a;  ///< maps B's model frame into A's model frame
  Scalar margin;     ///< delta plus a rounding allowance; bounding-volume tests only

  PairFrame(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
            Scalar delta)
      : b_to_a(pose_a.inverse() * pose_b) {
    // The culling tests are a filter in front of exact triangle tests, so widening them by a
    // rounding allowance never changes an answer; it keeps exactly touching configurations from
    // being culled by rounding in the box fit or in the separating-axis arithmetic.
    const Scalar scale = a.root().sphere.radius + b.root().sphere.radius +
                         a.root().sphere.center.norm() + b.root().sphere.center.norm() +
                         b_to_a.translation.norm();
    margin = delta + 1e-9 * scale;
  }
};

/// Depth-first dual traversal (paper, section 4 step 1). For each pair of leaves whose spheres and
/// OBBs are within `frame.margin`, calls on_leaf(leaf_a, leaf_b); a true return stops the walk.
template <class OnLeaf>
TraversalStats dual_traverse(const Model& a, const Model& b, const PairFrame& frame,
                             OnLeaf&& on_leaf) {
  TraversalStats stats;
  const auto nodes_a = a.nodes();
  const auto nodes_b = b.nodes();
  const Mat3& rot = frame.b_to_a.rotation;
  const Vec3& trans = frame.b_to_a.translation;

  // Each step pops one pair and pushes at most two, descending one tree by one level, so the
  // stack never holds more than depth(A) + depth(B) entries; the build caps each depth far below.
  struct Item {
    std::uint32_t ia, ib;
  };
  std::array<Item, 512> stack;
  std::size_t top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const Item item = stack[--top];
    const BvhNode& na = nodes_a[item.ia];
    const BvhNode& nb = nodes_b[item.ib];
    ++stats.node_pairs;

    const Vec3 cb = rot * nb.sphere.center + trans;
    const Scalar rsum = na.sphere.radius + nb.sphere.radius + frame.margin;
    if ((cb - na.sphere.center).squaredNorm() > rsum * rsum) {
      ++stats.sphere_rejects;
      continue;
    }
    Obb ob;
    ob.axes = rot * nb.obb.axes;
    ob.center = rot * nb.obb.center + trans;
    ob.half_extents = nb.obb.half_extents;
    if (!geometry::obb_overlap(na.obb, ob, frame.margin)) {
      ++stats.obb_rejects;
      continue;
    }

    const bool leaf_a = na.is_leaf();
    const bool leaf_b = nb.is_leaf();
    if (leaf_a && leaf_b) {
      ++stats.leaf_pairs;
      if (on_leaf(item.ia, item.ib)) break;
      continue;
    }
    assert(top + 2 <= stack.size());
    // Descend the larger volume (or the only internal one); right child pushed first so the
    // left subtree is visited first.
    if (leaf_b || (!leaf_a && na.sphere.radius >= nb.sphere.radius)) {
      stack[top++] = {na.first_or_right, item.ib};
      stack[top++] = {item.ia + 1, item.ib};
    } else {
      stack[top++] = {item.ia, nb.first_or_right};
      stack[top++] = {item.ia, item.ib + 1};
    }
  }
  return stats;
}

}  // namespace antcd::detail
