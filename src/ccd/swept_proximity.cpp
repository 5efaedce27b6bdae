// A boolean hierarchy traversal at an interval's midpoint with per-node-pair motion bounds; see
// swept_proximity.hpp.
#include "ccd/swept_proximity.hpp"

#include <antcd/ccd.hpp>
#include <antcd/geometry.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "bvh/traverse.hpp"

namespace antcd::ccd {
namespace {

/// Least distance of the segment from q to q + dq from the origin.
Scalar segment_gap(const Vec3& q, const Vec3& dq) {
  const Scalar len2 = dq.squaredNorm();
  const Scalar s = len2 > 0 ? std::clamp(-q.dot(dq) / len2, Scalar{0}, Scalar{1}) : 0;
  return (q + s * dq).norm();
}

/// A ball about a triangle's centroid holding its corners (radius rounded up).
struct Ball {
  Vec3 centre;
  Scalar radius;
};
Ball ball(const std::array<Vec3, 3>& t) {
  const Vec3 g = (t[0] + t[1] + t[2]) / 3;
  return {g, tolerance::widened(std::sqrt(std::max(
                 {(t[0] - g).squaredNorm(), (t[1] - g).squaredNorm(), (t[2] - g).squaredNorm()})))};
}

}  // namespace

bool interval_apart(const RigidPair& m, Scalar t0, Scalar t1, Scalar separation,
                    std::uint32_t budget, Scalar* slack) {
  const Scalar tm = (t0 + t1) / 2;
  // Half width, rounded up so that it covers both ends of [t0, t1].
  const Scalar h = tolerance::widened(std::max(t1 - tm, tm - t0));
  const Transform pa = interpolate_pose(m.a0, m.a1, tm);
  const Transform pb = interpolate_pose(m.b0, m.b1, tm);
  const detail::PairFrame frame(m.a, pa, m.b, pb, separation);
  const Mat3& rot = frame.b_to_a.rotation;
  const Vec3& trans = frame.b_to_a.translation;
  // Motion of a point at reach_a from A's axis relative to one at reach_b from B's over the
  // interval (ccd::Spin).
  const Spin& spin_a = m.spin_a;
  const Spin& spin_b = m.spin_b;
  const Scalar hs = h * m.speed;
  const Scalar ha = h * spin_a.theta;
  const Scalar hb = h * spin_b.theta;
  const auto motion = [&](Scalar reach_a, Scalar reach_b) {
    return tolerance::widened(hs + ha * reach_a + hb * reach_b);
  };
  // The ends of the interval, for the swept sphere test: a node's sphere turns into itself about
  // its centre, whose path strays from its chord by at most reach(c) theta^2 w^2 / 8 (an arc of
  // radius reach(c) at angular speed theta: second derivative reach(c) theta^2).
  const Transform pa0 = interpolate_pose(m.a0, m.a1, t0);
  const Transform pa1 = interpolate_pose(m.a0, m.a1, t1);
  const Transform pb0 = interpolate_pose(m.b0, m.b1, t0);
  const Transform pb1 = interpolate_pose(m.b0, m.b1, t1);
  const Scalar w2 = tolerance::widened((t1 - t0) * (t1 - t0) / 8);
  const Scalar bend_a = w2 * spin_a.theta * spin_a.theta;
  const Scalar bend_b = w2 * spin_b.theta * spin_b.theta;
  const auto nodes_a = m.a.nodes();
  const auto nodes_b = m.b.nodes();
  const LeafCorners corners_a = m.a.leaf_corners();
  const LeafCorners corners_b = m.b.leaf_corners();

  // Each step pops one pair and pushes at most two, one level down one tree: at most depth(A) +
  // depth(B) entries, each depth at most kMaxTreeLevels (antcd/bvh.hpp).
  std::array<std::pair<std::uint32_t, std::uint32_t>, 512> stack;
  static_assert(std::tuple_size_v<decltype(stack)> >= 2 * kMaxTreeLevels);
  std::size_t top = 0;
  stack[top++] = {0, 0};
  bool apart = true;
  Scalar least = std::numeric_limits<Scalar>::infinity();  // the smallest slack proven
  while (top > 0) {
    const auto [ia, ib] = stack[--top];
    if (budget-- == 0) {
      apart = false;
      break;
    }
    const BvhNode& na = nodes_a[ia];
    const BvhNode& nb = nodes_b[ib];
    const Scalar ra = na.radius;
    const Scalar rb = nb.radius;
    const Scalar reach_ca = spin_a.reach(na.center);
    const Scalar reach_cb = spin_b.reach(nb.center);
    // A ball turns into itself about its centre: only the centres' motion counts for the spheres.
    const Vec3 cb = rot * nb.center + trans;
    const Scalar rsum = ra + rb + frame.margin + motion(reach_ca, reach_cb);
    const Scalar centres = (cb - na.center).norm();
    if (centres > rsum) {
      least = std::min(least, centres - rsum);
      continue;
    }
    // B's centre relative to A's at both ends (world frame); in between, the chord from q0 to
    // q0 + dq up to the bends.
    const Vec3 q0 = pb0.apply(nb.center) - pa0.apply(na.center);
    const Vec3 dq = pb1.apply(nb.center) - pa1.apply(na.center) - q0;
    const Scalar bends = bend_a * reach_ca + bend_b * reach_cb;
    {
      const Scalar gap = segment_gap(q0, dq);
      const Scalar need = tolerance::widened(ra + rb + frame.margin + bends);
      if (gap > need) {
        least = std::min(least, gap - need);
        continue;
      }
    }
    // A box also turns about its centre (Spin::node_reach).
    const Scalar turn_a = spin_a.node_reach(na);
    const Scalar turn_b = spin_b.node_reach(nb);
    const Scalar margin = frame.margin + motion(reach_ca + turn_a, reach_cb + turn_b);
    const detail::PosedAxes axes_b(nb, rot);
    const Vec3 a2 = na.axis0.cross(na.axis1);
    if (detail::obb_disjoint<detail::BoxTest::full>(na, a2, nb, axes_b, cb, margin)) {
      least = 0;  // apart by more than the margin, by how much is not measured
      continue;
    }
    {
      // Swept boxes: each box keeps its orientation at tm and its centre runs along the chord;
      // a node's points stray from that by at most theta h node_reach (turning about the centre; at
      // most the radius) plus the
      // centre's bend. Face axes of both boxes, B's extents widened by the sweep's projection.
      const Mat3 to_a = pa.rotation.transpose();
      const Vec3 mid = to_a * (q0 + dq / 2);
      const Vec3 half_sweep = to_a * (dq / 2);
      const Scalar m2 = tolerance::widened(frame.margin + bends +
                                           h * (spin_a.theta * turn_a + spin_b.theta * turn_b));
      Mat3 r;
      r << na.axis0.dot(axes_b.b0), na.axis0.dot(axes_b.b1), na.axis0.dot(axes_b.b2),  //
          na.axis1.dot(axes_b.b0), na.axis1.dot(axes_b.b1), na.axis1.dot(axes_b.b2),   //
          a2.dot(axes_b.b0), a2.dot(axes_b.b1), a2.dot(axes_b.b2);
      const Mat3 abs_r = r.cwiseAbs();
      const Vec3 ea = na.half_extents().array() + m2;
      const Vec3 eb = nb.half_extents();
      const Vec3 ta(na.axis0.dot(mid), na.axis1.dot(mid), a2.dot(mid));
      const Vec3 sa(na.axis0.dot(half_sweep), na.axis1.dot(half_sweep), a2.dot(half_sweep));
      const Vec3 tb = r.transpose() * ta;
      const Vec3 sb = r.transpose() * sa;
      const Vec3 reach_a = ea + abs_r * eb + sa.cwiseAbs();
      const Vec3 reach_b = eb + abs_r.transpose() * ea + sb.cwiseAbs();
      if ((ta.cwiseAbs().array() > reach_a.array()).any() ||
          (tb.cwiseAbs().array() > reach_b.array()).any()) {
        least = 0;
        continue;
      }
    }
    if (na.is_leaf() && nb.is_leaf()) {
      for (std::uint32_t i = 0; i < na.count && apart; ++i) {
        const auto ta = corners_a.triangle(std::size_t{na.first_or_right} + i);
        const Scalar reach_a =
            std::max({spin_a.reach(ta[0]), spin_a.reach(ta[1]), spin_a.reach(ta[2])});
        const Ball sa = ball(ta);
        const Vec3 na_unit = (ta[1] - ta[0]).cross(ta[2] - ta[0]).normalized();
        const Vec3 sa0 = pa0.apply(sa.centre);
        const Vec3 sa1 = pa1.apply(sa.centre);
        for (std::uint32_t j = 0; j < nb.count; ++j) {
          const auto tb = corners_b.triangle(std::size_t{nb.first_or_right} + j);
          const Ball sb = ball(tb);
          {
            const Vec3 g0 = pb0.apply(sb.centre) - sa0;
            const Scalar gap = segment_gap(g0, pb1.apply(sb.centre) - sa1 - g0);
            const Scalar need = tolerance::widened(sa.radius + sb.radius + frame.margin +
                                                   bend_a * spin_a.reach(sa.centre) +
                                                   bend_b * spin_b.reach(sb.centre));
            if (gap > need) {
              least = std::min(least, gap - need);
              continue;
            }
          }
          const Scalar reach_b =
              std::max({spin_b.reach(tb[0]), spin_b.reach(tb[1]), spin_b.reach(tb[2])});
          const std::array<Vec3, 3> yb{rot * tb[0] + trans, rot * tb[1] + trans,
                                       rot * tb[2] + trans};
          const Scalar need = frame.margin + motion(reach_a, reach_b);
          // The gaps along the two normals first: parallel faces (a spinning disc beside a
          // plate) are proven apart without the exact distance.
          const Vec3 nb = (yb[1] - yb[0]).cross(yb[2] - yb[0]).normalized();
          if (const Scalar g = std::max({axis_gap(na_unit, ta, yb), axis_gap(na_unit, yb, ta),
                                         axis_gap(nb, yb, ta), axis_gap(nb, ta, yb)});
              g > need) {
            least = std::min(least, g - need);
            continue;
          }
          const Scalar d =
              geometry::triangle_distance(ta[0], ta[1], ta[2], yb[0], yb[1], yb[2]).distance;
          if (!(d > need)) {
            apart = false;
            break;
          }
          least = std::min(least, d - need);
        }
      }
      if (!apart) break;
      continue;
    }
    assert(top + 2 <= stack.size());
    // Descend the larger sphere (or the only internal node); the child nearer the other node is
    // visited first, so a pair that cannot be proven apart is met early.
    if (nb.is_leaf() || (!na.is_leaf() && ra >= rb)) {
      std::uint32_t first = ia + 1, second = na.first_or_right;
      if ((nodes_a[second].center - cb).squaredNorm() <
          (nodes_a[first].center - cb).squaredNorm()) {
        std::swap(first, second);
      }
      stack[top++] = {second, ib};
      stack[top++] = {first, ib};
    } else {
      std::uint32_t first = ib + 1, second = nb.first_or_right;
      const auto dist2 = [&](std::uint32_t k) {
        return (rot * nodes_b[k].center + trans - na.center).squaredNorm();
      };
      if (dist2(second) < dist2(first)) std::swap(first, second);
      stack[top++] = {ia, second};
      stack[top++] = {ia, first};
    }
  }
  if (slack != nullptr && apart) *slack = std::min(*slack, least);
  return apart;
}

}  // namespace antcd::ccd
