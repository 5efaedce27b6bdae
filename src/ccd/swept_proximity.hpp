// Private: a proof that two rigidly moving models stay apart over a time interval, by one boolean
// hierarchy traversal at the interval's midpoint whose node pairs are widened by their own motion
// bound over half the interval. Used by the mesh sweep (sweep.cpp).
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <cstdint>

#include "ccd/motion.hpp"

namespace antcd::ccd {

/// Two rigid motions over t in [0, 1] (antcd/ccd.hpp's interpolation) and the bounds of their
/// relative motion: `speed` >= |(T_a1 - T_a0) - (T_b1 - T_b0)|, theta_a and theta_b >= the
/// rotation angles (ccd::rotation_angle), all rounded up.
struct RigidPair {
  const Model& a;
  const Transform& a0;
  const Transform& a1;
  const Model& b;
  const Transform& b0;
  const Transform& b1;
  Scalar speed = 0;
  Scalar theta_a = 0;
  Scalar theta_b = 0;
};

/// The bounds of A moving from a0 to a1 and B from b0 to b1 (the result keeps references to its
/// arguments, which must outlive it).
inline RigidPair rigid_pair(const Model& a, const Transform& a0, const Transform& a1,
                            const Model& b, const Transform& b0, const Transform& b1) {
  const Vec3 move = (a1.translation - a0.translation) - (b1.translation - b0.translation);
  return {a,
          a0,
          a1,
          b,
          b0,
          b1,
          tolerance::widened(move.norm()),
          rotation_angle(a0.rotation, a1.rotation),
          rotation_angle(b0.rotation, b1.rotation)};
}

/// True when A and B are proven to stay more than `separation` apart at every t in [t0, t1]
/// (0 <= t0 <= t1 <= 1); false when not proven (they may or may not come that close).
///
/// Bound: over |t - tm| <= h (tm the midpoint, h the half width) a model point p moves relative to
/// the other model's point q by at most h (speed + theta_a |p| + theta_b |q|) (linear translation;
/// the slerp turns p about the model origin by at most theta |t - tm|, a chord of at most
/// theta |t - tm| |p|), with |p| <= |centre| + radius for the points of a node's sphere (model
/// frame). So a node pair whose spheres or boxes at tm are farther apart than separation plus that
/// pair's own bound stays apart over the interval, and so does a triangle pair whose exact distance
/// at tm exceeds separation plus its bound (|p| up to its farthest corner). The walk stops at the
/// first triangle pair it cannot prove apart. Rounding: the traversal's volume allowance (kVolume
/// of the scene's size) is added to every margin; the caller adds its own for the poses and t.
/// When proven apart and `slack` is given, *slack is lowered to at most the amount by which every
/// pair stayed beyond separation (0 where only a box test, which measures nothing, proved it): the
/// models stay at least separation + slack apart over the interval.
/// The walk gives up (false) after examining `budget` node pairs.
bool interval_apart(const RigidPair& m, Scalar t0, Scalar t1, Scalar separation,
                    std::uint32_t budget, Scalar* slack = nullptr);

}  // namespace antcd::ccd
