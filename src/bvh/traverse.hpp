// Private: the depth-first dual traversal shared by every narrow phase.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/tolerances.hpp>

#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>

#include "bvh/face_test.hpp"
#include "geometry/obb_sat.hpp"

namespace antcd::detail {

/// pose_a^-1 ∘ pose_b: the placement of B's model frame in A's model frame, for two models placed
/// at pose_a and pose_b. Every pair query forms it here, once. A pose both models share never
/// changes an answer: bitwise-equal rotations give exactly the identity rotation, and equal poses
/// exactly the identity transform (R^T (t_b - t_a) with t_b == t_a is zero), so exactly touching
/// models stay exactly touching.
inline Transform relative_pose(const Transform& pose_a, const Transform& pose_b) {
  Transform out;
  const Mat3 rt = pose_a.rotation.transpose();
  if (pose_a.rotation == pose_b.rotation) {
    out.rotation = Mat3::Identity();
  } else {
    out.rotation.noalias() = rt * pose_b.rotation;
  }
  out.translation.noalias() = rt * (pose_b.translation - pose_a.translation);
  return out;
}

/// Relative placement of model B in model A's frame plus the culling margin.
struct PairFrame {
  Transform b_to_a;  ///< maps B's model frame into A's model frame
  Scalar margin;     ///< delta plus a rounding allowance; bounding-volume tests only
  float margin_f;    ///< margin rounded to float, for float_face_separated
  bool float_faces;  ///< the face-axes box test may run in float (bvh/face_test.hpp)

  PairFrame(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
            Scalar delta)
      : b_to_a(relative_pose(pose_a, pose_b)) {
    // The culling tests are a filter in front of exact triangle tests, so widening them by a
    // rounding allowance never changes an answer; it keeps exactly touching configurations from
    // being culled by rounding in the box fit or in the separating-axis arithmetic.
    const Scalar scale = a.root().radius + b.root().radius + a.root().center.norm() +
                         b.root().center.norm() + b_to_a.translation.norm();
    margin = delta + tolerance::kVolume * scale;
    margin_f = static_cast<float>(margin);
    // Float's range holds every quantity of the box tests of such scenes (bvh/face_test.hpp).
    float_faces = FloatFaceAxes::kAvailable && scale >= 1e-20 && scale <= 1e30 && margin <= 1e30;
  }
};

/// B's node box axes mapped into A's model frame by the rotation `rot`: R b0, R b1 and their cross
/// product as B's third axis, equal to R (b0 x b1) up to rounding (which the margin covers, like
/// the rest of the separating-axis arithmetic); with kFloat, also as float lanes.
template <bool kFloat = false>
struct PosedAxes {
  Vec3 b0 = Vec3::Zero(), b1 = Vec3::Zero(), b2 = Vec3::Zero();
  FloatFaceAxes f;  ///< with kFloat: b0, b1, b2 and B's half extents in float
  PosedAxes() = default;
  PosedAxes(const BvhNode& b, const Mat3& rot) : b0(rot * b.axis0), b1(rot * b.axis1) {
    b2 = b0.cross(b1);
    if constexpr (kFloat) f = FloatFaceAxes(b0, b1, b2, b);
  }
};

/// The box test of a traversal. full: the 15 axes of geometry::obb_overlap, every box pair culled
/// that those separate. faces: the six face axes only (geometry::detail::obb_face_separated), for
/// walks whose leaves go on to exact triangle tests: a box pair that only an edge-edge axis
/// separates holds no triangle pair within the margin either, so the extra node pairs it lets
/// through never add a contact and never change the order in which contacts are found; they cost
/// less than the nine cross axes on every node pair that overlaps (most node pairs of an exact
/// query; the pair and scene sections of bench/icount.cpp measure it).
enum class BoxTest { full, faces };

/// Separating-axis test between A's node box (third axis `a2` = a.axis0 x a.axis1) and B's node
/// box with axes `rb` and centre `cb` in A's model frame: the axes of kBox with the tolerances and
/// margin of geometry::obb_overlap, inlined into the traversal. True when a separating axis was
/// found.
template <BoxTest kBox, bool kFloat>
[[gnu::always_inline]] inline bool obb_disjoint(const BvhNode& a, const Vec3& a2, const BvhNode& b,
                                                const PosedAxes<kFloat>& rb, const Vec3& cb,
                                                Scalar margin) {
  const Vec3 d = cb - a.center;
  Mat3 r;
  r << a.axis0.dot(rb.b0), a.axis0.dot(rb.b1), a.axis0.dot(rb.b2),  //
      a.axis1.dot(rb.b0), a.axis1.dot(rb.b1), a.axis1.dot(rb.b2),   //
      a2.dot(rb.b0), a2.dot(rb.b1), a2.dot(rb.b2);
  const Vec3 t(a.axis0.dot(d), a.axis1.dot(d), a2.dot(d));
  const Vec3 ea = a.half_extents().array() + margin;
  if constexpr (kBox == BoxTest::faces) {
    return geometry::detail::obb_face_separated(ea, b.half_extents(), r,
                                                geometry::detail::obb_abs_rotation(r), t);
  } else {
    return geometry::detail::obb_separated(ea, b.half_extents(), r, t);
  }
}

/// Which triangles of a leaf (bits of `live`, triangle k of the leaf at bit k) may come within the
/// margin of a box: those the 13-axis test does not separate from it. The leaf's triangles
/// (leaf triangles first .. first + count of `corners`) are mapped into the box's coordinates by
/// u = m * v + off; `e` is the box's half extents widened by the margin.
inline std::uint32_t live_triangles(const LeafCorners& corners, std::uint32_t first,
                                    std::uint32_t count, std::uint32_t live, const Mat3& m,
                                    const Vec3& off, const Vec3& e) {
  for (std::uint32_t k = 0; k < count; ++k) {
    if ((live >> k & 1u) == 0) continue;
    const std::size_t t = std::size_t{first} + k;
    if (geometry::detail::triangle_box_separated(m * corners(t, 0) + off, m * corners(t, 1) + off,
                                                 m * corners(t, 2) + off, e)) {
      live &= ~(1u << k);
    }
  }
  return live;
}

/// Leaves of at most this many triangles have their triangles tested one by one against a smaller
/// node of the other model (one bit each in a 32-bit mask) ...
inline constexpr std::uint32_t kMaskedLeaf = 32;
/// ... when the leaf's sphere is more than this many times the node's. With 1 (any smaller node)
/// the extra tests made the median boolean query of FCL's protocol (bench/pair_protocol_bench)
/// slower (0.38-0.45 of FCL's against 0.30-0.37 without masks, one run each, a busy machine);
/// with 2 it stayed at 0.31-0.37 and the large-leaf cases kept their gain.
inline constexpr Scalar kMaskRatio = 2;

/// Depth-first dual traversal (paper, section 4 step 1). For each pair of leaves whose spheres and
/// OBBs are within `frame.margin`, calls on_leaf(leaf_a, leaf_b); a true return stops the walk.
///
/// When on_leaf also takes two masks, on_leaf(leaf_a, leaf_b, live_a, live_b), a leaf of 2 to
/// kMaskedLeaf triangles met by a node whose sphere is more than kMaskRatio times smaller has its
/// triangles tested one by one against that node's box (live_triangles), and the pair is culled
/// when none is left; the surviving set (bit k: the leaf's triangle k; bits past the leaf's count
/// are set) is carried down the other model's subtree and handed to on_leaf, which needs to test
/// only those: every triangle left out is farther than the margin from every triangle of the other
/// leaf. This keeps a large leaf (a few big triangles of one mesh around a small part of the other)
/// from pairing with every leaf of the small part.
///
/// kNearestFirst (for walks that stop at the first hit): of the two children descended, the one
/// whose sphere centre is nearer the other node's centre is visited first. Every overlapping leaf
/// pair is still reached unless on_leaf stops the walk; only the order changes.
///
/// kBox: the box test after the sphere test (BoxTest); with faces, on_leaf also meets leaf pairs
/// whose boxes only an edge-edge axis separates.
template <bool kNearestFirst = false, BoxTest kBox = BoxTest::full, class OnLeaf>
TraversalStats dual_traverse(const Model& a, const Model& b, const PairFrame& frame,
                             OnLeaf&& on_leaf) {
  TraversalStats stats;
  const auto nodes_a = a.nodes();
  const auto nodes_b = b.nodes();
  const Mat3& rot = frame.b_to_a.rotation;
  const Vec3& trans = frame.b_to_a.translation;

  constexpr bool kMasks =
      std::is_invocable_v<OnLeaf&, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
  constexpr std::uint32_t kAll = ~std::uint32_t{0};
  // Each step pops one pair and pushes at most two, descending one tree by one level, so the
  // stack never holds more than depth(A) + depth(B) entries; every Model's depth is at most
  // kMaxTreeLevels (the build's bound; model files with deeper trees are refused).
  struct Item {
    std::uint32_t ia, ib;
    std::uint32_t live_a, live_b;  // see above; kAll when not masked
  };
  std::array<Item, 512> stack;
  static_assert(std::tuple_size_v<decltype(stack)> >= 2 * kMaxTreeLevels);
  std::size_t top = 0;
  constexpr std::uint32_t kNone = ~std::uint32_t{0};
  // The float face test needs the placed axes in float lanes too.
  constexpr bool kFloat = kBox == BoxTest::faces && FloatFaceAxes::kAvailable;
  // A node's placement in the other model's frame (centre, then box axes) and a node's own third
  // axis, each kept while consecutive pairs share the node: the same values as computed afresh,
  // without the cost. A pair is tested in A's frame (B's node placed) or in B's (A's node placed
  // by the inverse rotation), whichever placement is at hand: one tree is descended under a fixed
  // node of the other, so placing the fixed node once saves placing each node of the other tree.
  // The sphere and box tests are filters whose rounding the margin covers in either frame.
  struct Placed {
    std::uint32_t centre_of = kNone;  // the node whose centre c holds
    std::uint32_t axes_of = kNone;    // the node whose placed axes r hold
    std::uint32_t third_of = kNone;   // the node whose own third axis holds
    Vec3 c = Vec3::Zero();
    PosedAxes<kFloat> r;
    Vec3 third = Vec3::Zero();
  };
  Placed pb;  // B's nodes in A's frame; third: A's node's own third axis
  Placed pa;  // A's nodes in B's frame; third: B's node's own third axis
  const Mat3 irot = rot.transpose();
  const auto centre_b = [&](std::uint32_t ib) -> const Vec3& {
    if (ib != pb.centre_of) {
      pb.centre_of = ib;
      pb.c = rot * nodes_b[ib].center + trans;
    }
    return pb.c;
  };
  const auto centre_a = [&](std::uint32_t ia) -> const Vec3& {
    if (ia != pa.centre_of) {
      pa.centre_of = ia;
      pa.c = rot.transpose() * (nodes_a[ia].center - trans);  // as nearest-first always formed it
    }
    return pa.c;
  };
  std::uint32_t last_a = kNone;
  stack[top++] = {0, 0, kAll, kAll};
  while (top > 0) {
    Item item = stack[--top];
    const BvhNode& na = nodes_a[item.ia];
    const BvhNode& nb = nodes_b[item.ib];
    ++stats.node_pairs;

    // In B's frame when A's node is placed already, or when neither is and A's node stays (B's
    // tree is being descended under it). Exact walks only: the others (the random methods') keep
    // exactly the culls they always had, since the leaf pairs they meet feed their sampling.
    const bool in_b = kBox == BoxTest::faces && item.ib != pb.centre_of &&
                      (item.ia == pa.centre_of || item.ia == last_a);
    last_a = item.ia;
    const Scalar radius_a = na.radius;
    const Scalar radius_b = nb.radius;
    const Scalar rsum = radius_a + radius_b + frame.margin;
    const Scalar dist2 = in_b ? (centre_a(item.ia) - nb.center).squaredNorm()
                              : (centre_b(item.ib) - na.center).squaredNorm();
    if (dist2 > rsum * rsum) {
      ++stats.sphere_rejects;
      continue;
    }
    // The box test of node `fixed` (own axes) and node `moved` placed in fixed's model frame by
    // `place` (p.c already holds moved's placed centre). Forced inline: as a call it cost 3.5 % of
    // pair_contacts' instructions.
    const auto box_disjoint = [&](Placed & p, const BvhNode& fixed, std::uint32_t i_fixed,
                                  const BvhNode& moved, std::uint32_t i_moved, const Mat3& place)
        __attribute__((always_inline)) {
      if (i_moved != p.axes_of) {
        p.axes_of = i_moved;
        p.r = PosedAxes<kFloat>(moved, place);
      }
      if (i_fixed != p.third_of) {
        p.third_of = i_fixed;
        p.third = fixed.axis0.cross(fixed.axis1);
      }
      if constexpr (kFloat) {  // the face axes in float where the frame allows
        if (frame.float_faces) {
          return float_face_separated(fixed, p.third, p.r.f, p.c - fixed.center, frame.margin_f);
        }
      }
      return obb_disjoint<kBox>(fixed, p.third, moved, p.r, p.c, frame.margin);
    };
    const bool disjoint = in_b ? box_disjoint(pa, nb, item.ib, na, item.ia, irot)
                               : box_disjoint(pb, na, item.ia, nb, item.ib, rot);
    if (disjoint) {
      ++stats.obb_rejects;
      continue;
    }

    const bool leaf_a = na.is_leaf();
    const bool leaf_b = nb.is_leaf();
    if constexpr (kMasks) {
      if (leaf_a && na.count > 1 && na.count <= kMaskedLeaf && radius_a > kMaskRatio * radius_b) {
        // A's triangles in B's node box coordinates: u = (R b)^T (v - (R c_b + t)).
        const Mat3 m = (rot * nb.axes()).transpose();
        const Vec3 off = -(m * centre_b(item.ib));
        item.live_a = live_triangles(a.leaf_corners(), na.first_or_right, na.count, item.live_a, m,
                                     off, nb.half_extents().array() + frame.margin);
        if ((item.live_a & (kAll >> (32 - na.count))) == 0) {
          ++stats.triangle_rejects;
          continue;
        }
      }
      if (leaf_b && nb.count > 1 && nb.count <= kMaskedLeaf && radius_b > kMaskRatio * radius_a) {
        // B's triangles in A's node box coordinates: u = a^T (R v + t - c_a).
        const Mat3 axes_a = na.axes();
        const Mat3 m = axes_a.transpose() * rot;
        const Vec3 off = axes_a.transpose() * (trans - na.center);
        item.live_b = live_triangles(b.leaf_corners(), nb.first_or_right, nb.count, item.live_b, m,
                                     off, na.half_extents().array() + frame.margin);
        if ((item.live_b & (kAll >> (32 - nb.count))) == 0) {
          ++stats.triangle_rejects;
          continue;
        }
      }
    }
    if (leaf_a && leaf_b) {
      ++stats.leaf_pairs;
      if constexpr (kMasks) {
        if (on_leaf(item.ia, item.ib, item.live_a, item.live_b)) break;
      } else {
        if (on_leaf(item.ia, item.ib)) break;
      }
      continue;
    }
    assert(top + 2 <= stack.size());
    // Descend the larger volume (or the only internal one); right child pushed first so the
    // left subtree is visited first.
    if (leaf_b || (!leaf_a && radius_a >= radius_b)) {
      std::uint32_t first = item.ia + 1;
      std::uint32_t second = na.first_or_right;
      if constexpr (kNearestFirst) {
        const Vec3& cb = centre_b(item.ib);
        if ((nodes_a[second].center - cb).squaredNorm() <
            (nodes_a[first].center - cb).squaredNorm()) {
          std::swap(first, second);
        }
      }
      stack[top++] = {second, item.ib, kAll, item.live_b};
      stack[top++] = {first, item.ib, kAll, item.live_b};
    } else {
      std::uint32_t first = item.ib + 1;
      std::uint32_t second = nb.first_or_right;
      if constexpr (kNearestFirst) {
        const Vec3& ca = centre_a(item.ia);  // A's centre in B's frame
        if ((nodes_b[second].center - ca).squaredNorm() <
            (nodes_b[first].center - ca).squaredNorm()) {
          std::swap(first, second);
        }
      }
      stack[top++] = {item.ia, second, item.live_a, kAll};
      stack[top++] = {item.ia, first, item.live_a, kAll};
    }
  }
  return stats;
}

}  // namespace antcd::detail
