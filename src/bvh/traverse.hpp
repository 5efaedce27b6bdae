// Private: the depth-first dual traversal shared by every narrow phase.
#pragma once

#include <antcd/bvh.hpp>

#include <array>
#include <cassert>
#include <cmath>
#include <utility>

#include "geometry/obb_sat.hpp"

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

/// Separating-axis test between A's node box and B's node box, B given in its model frame with the
/// rigid motion (rot, trans) into A's model frame: the 15 axes, tolerances and margin of
/// geometry::obb_overlap, inlined into the traversal. True when a separating axis was found.
inline bool obb_disjoint(const Obb& a, const Obb& b, const Mat3& rot, const Vec3& trans,
                         Scalar margin) {
  const Mat3 rb = rot * b.axes;
  const Mat3 r = a.axes.transpose() * rb;
  const Vec3 t = a.axes.transpose() * (rot * b.center + trans - a.center);
  return geometry::detail::obb_separated(a.half_extents.array() + margin, b.half_extents, r, t);
}

/// Depth-first dual traversal (paper, section 4 step 1). For each pair of leaves whose spheres and
/// OBBs are within `frame.margin`, calls on_leaf(leaf_a, leaf_b); a true return stops the walk.
/// kNearestFirst (for walks that stop at the first hit): of the two children descended, the one
/// whose sphere centre is nearer the other node's centre is visited first. Every overlapping leaf
/// pair is still reached unless on_leaf stops the walk; only the order changes.
template <bool kNearestFirst = false, class OnLeaf>
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
    if (obb_disjoint(na.obb, nb.obb, rot, trans, frame.margin)) {
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
      std::uint32_t first = item.ia + 1;
      std::uint32_t second = na.first_or_right;
      if constexpr (kNearestFirst) {
        if ((nodes_a[second].sphere.center - cb).squaredNorm() <
            (nodes_a[first].sphere.center - cb).squaredNorm()) {
          std::swap(first, second);
        }
      }
      stack[top++] = {second, item.ib};
      stack[top++] = {first, item.ib};
    } else {
      std::uint32_t first = item.ib + 1;
      std::uint32_t second = nb.first_or_right;
      if constexpr (kNearestFirst) {
        // A's centre in B's frame.
        const Vec3 ca = rot.transpose() * (na.sphere.center - trans);
        if ((nodes_b[second].sphere.center - ca).squaredNorm() <
            (nodes_b[first].sphere.center - ca).squaredNorm()) {
          std::swap(first, second);
        }
      }
      stack[top++] = {item.ia, second};
      stack[top++] = {item.ia, first};
    }
  }
  return stats;
}

}  // namespace antcd::detail
