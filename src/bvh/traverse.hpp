// Private: the depth-first dual traversal shared by every narrow phase.
#pragma once

#include <antcd/bvh.hpp>

#include <array>
#include <cassert>
#include <cmath>
#include <utility>

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
  constexpr Scalar kEps = 1e-12;  // as geometry::obb_overlap: near-parallel edge pairs
  const Mat3 rb = rot * b.axes;
  const Mat3 r = a.axes.transpose() * rb;
  const Vec3 t = a.axes.transpose() * (rot * b.center + trans - a.center);
  const Mat3 ar = r.cwiseAbs().array() + kEps;
  const Vec3 ea = a.half_extents.array() + margin;
  const Vec3& eb = b.half_extents;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > ea[i] + ar.row(i).dot(eb)) return true;
  }
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(r.col(j))) > ar.col(j).dot(ea) + eb[j]) return true;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const Scalar ra = ea[i1] * ar(i2, j) + ea[i2] * ar(i1, j);
      const Scalar rb2 = eb[j1] * ar(i, j2) + eb[j2] * ar(i, j1);
      const Scalar dist = std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j));
      if (dist > ra + rb2) return true;
    }
  }
  return false;
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
