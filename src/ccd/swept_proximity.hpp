// Private: a proof that two rigidly moving models stay apart over a time interval, by one boolean
// hierarchy traversal at the interval's midpoint whose node pairs are widened by their own motion
// bound over half the interval. Used by the mesh sweep (sweep.cpp).
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <algorithm>
#include <array>
#include <cstdint>

#include "ccd/motion.hpp"

namespace antcd::ccd {

/// Two rigid motions over t in [0, 1] (antcd/ccd.hpp's interpolation) and the bounds of their
/// relative motion: `speed` >= |(T_a1 - T_a0) - (T_b1 - T_b0)| (rounded up), and each model's turn
/// (ccd::Spin: its angle, and the reach of a point from its axis).
struct RigidPair {
  const Model& a;
  const Transform& a0;
  const Transform& a1;
  const Model& b;
  const Transform& b0;
  const Transform& b1;
  Scalar speed = 0;
  Spin spin_a;
  Spin spin_b;
};

/// The bounds of A moving from a0 to a1 and B from b0 to b1 (the result keeps references to its
/// arguments, which must outlive it).
inline RigidPair rigid_pair(const Model& a, const Transform& a0, const Transform& a1,
                            const Model& b, const Transform& b0, const Transform& b1) {
  const Vec3 move = (a1.translation - a0.translation) - (b1.translation - b0.translation);
  // stableNorm: a motion of 1e-300 has a speed of 1e-300, not the 0 its squares underflow to.
  const Scalar speed = tolerance::widened(move.stableNorm());
  return {a,
          a0,
          a1,
          b,
          b0,
          b1,
          speed,
          model_spin(a, a0.rotation, a1.rotation, speed),
          model_spin(b, b0.rotation, b1.rotation, speed)};
}

/// The gap between the points x and the points y along the unit axis n (x on its high side):
/// min n . x - max n . y, a lower bound of the distance of their convex hulls when positive.
inline Scalar axis_gap(const Vec3& n, const std::array<Vec3, 3>& x, const std::array<Vec3, 3>& y) {
  return std::min({n.dot(x[0]), n.dot(x[1]), n.dot(x[2])}) -
         std::max({n.dot(y[0]), n.dot(y[1]), n.dot(y[2])});
}

/// mu: how fast the distance of the two models may fall, per unit of t, over the whole motion:
/// speed + theta_a reach_a + theta_b reach_b (ccd::model_reach), rounded up.
inline Scalar motion_bound(const RigidPair& m) {
  return tolerance::widened(m.speed + m.spin_a.theta * model_reach(m.a, m.spin_a) +
                            m.spin_b.theta * model_reach(m.b, m.spin_b));
}

/// True when A and B are proven to stay more than `separation` apart at every t in [t0, t1]
/// (0 <= t0 <= t1 <= 1); false when not proven (they may or may not come that close).
///
/// Bound: over |t - tm| <= h (tm the midpoint, h the half width) a model point p moves relative to
/// the other model's point q by at most h (speed + theta_a reach_a(p) + theta_b reach_b(q))
/// (linear translation; the slerp turns p about its model's axis, on a circle of radius reach(p),
/// at theta reach(p) per unit time; ccd::Spin), with reach(p) <= reach(centre) + radius for the
/// points of a node's sphere (model frame). So a node pair whose spheres or boxes at tm are farther
/// apart than separation plus that pair's own bound stays apart over the interval, and so does a
/// triangle pair whose exact distance at tm exceeds separation plus its bound (|p| up to its
/// farthest corner). The walk stops at the first triangle pair it cannot prove apart. Rounding: the
/// traversal's volume allowance (kVolume of the scene's size) is added to every margin; the caller
/// adds its own for the poses and t. When proven apart and `slack` is given, *slack is lowered to
/// at most the amount by which every pair stayed beyond separation (0 where only a box test, which
/// measures nothing, proved it): the models stay at least separation + slack apart over the
/// interval. The walk gives up (false) after examining `budget` node pairs.
bool interval_apart(const RigidPair& m, Scalar t0, Scalar t1, Scalar separation,
                    std::uint32_t budget, Scalar* slack = nullptr);

}  // namespace antcd::ccd
