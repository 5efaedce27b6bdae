// Private: the earliest contact of two rigidly moving models by one traversal of both hierarchies
// in which every node pair and every triangle pair advances in time on its own (conservative
// advancement per pair, after Tang, Kim and Manocha's C2A, 2009). Used by the mesh sweep
// (sweep.cpp) after its interval proofs.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include <cstdint>
#include <span>

#include "ccd/swept_proximity.hpp"

namespace antcd::ccd {

/// What first_contact() decided.
struct FirstContact {
  enum class Outcome : std::uint8_t {
    miss,     ///< no pair comes within the separation in [t0, 1]: a proof
    hit,      ///< toi and the pair below
    gave_up,  ///< the work budget ran out: only toi is decided (see below)
  };
  Outcome outcome = Outcome::miss;
  /// When hit: the earliest time at which a triangle pair was within reach (see first_contact).
  /// When gave_up: the time the search had reached; no pair comes within the separation before.
  Scalar toi = 1;
  /// When hit: that pair (mesh triangle indices) and its distance at toi.
  std::uint32_t triangle_a = 0;
  std::uint32_t triangle_b = 0;
  Scalar distance = 0;
  /// When hit: the pair intersects at toi (exact test on the posed corners) or its distance there
  /// is within the separation less the allowance.
  bool proven = false;
  /// Node pairs and triangle pairs examined (each examination at one time).
  std::uint64_t pairs = 0;
};

/// Limits of one first_contact() call.
struct FirstContactLimits {
  /// Node pairs and triangle pairs examined (each examination at one time) before giving up.
  std::uint64_t pairs = 5000;
};

/// Searches [t0, 1] for the earliest time at which a triangle pair of A and B comes within
/// `separation` (nothing touches before t0 is the caller's to know).
///
/// A pair of nodes, or of triangles, apart at time t stays apart for a step: node spheres and
/// triangle pairs by pair_step() below (for spheres the centres as the point sets: a ball turns
/// into itself about its centre, so only the centres' paths count), node boxes by their gap over
/// |relative translation| + theta_a (reach_a(centre_a) + node_reach_a) + theta_b (...) (reach: the
/// distance from the model's turning axis, ccd::Spin). Pairs are examined earliest first
/// (a heap); each advances from its parent's time in steps of that size until it may touch (then
/// its children are examined from there) or passes 1 (then it is dropped). Chord tests
/// (first_contact.cpp, nodes() and triangles()) let a pair jump several steps at once where the
/// paths, in A's frame, stay near their chords. The first triangle pair examined whose exact
/// distance is within separation + allowance + stop_gap, or which the exact test finds
/// intersecting, gives the result: every pair still queued is proven apart until its own later
/// time, so no pair is within separation before toi.
/// Rounding: `allowance` (scene's size times kArithmetic) is taken off every triangle distance and
/// `volume` (kVolume of the scene's size) off every node distance, as in the sweep.
/// Exported for the tests (tests/ccd/first_contact_test.cpp). Thread safety: reads its models only;
/// its pair queues are the calling thread's own (kept between calls, so a traversal allocates
/// only when it outgrows the earlier ones; queues grown beyond 65 536 pairs are freed after use).
ANTCD_API FirstContact first_contact(const RigidPair& m, Scalar t0, Scalar separation,
                                     Scalar allowance, Scalar volume, Scalar stop_gap,
                                     const FirstContactLimits& limits = {});

/// How long a pair of convex sets (two triangles, or two balls' centres) stays apart from time s
/// on: `gap` > 0 the amount by which their separation along the unit direction n (A's frame at s,
/// pointing from B towards A; `n_error` >= the error of its computed direction) exceeds what
/// must stay between them, `v` the relative translation velocity of A against B in A's frame,
/// `b_to_a` the rotation of B's model frame into A's at s, `a_points` / `b_points` the sets'
/// corners (or centres) in their own model frames. The result (>= 0, possibly infinite: never
/// nearer) is the larger of two steps, each a proof:
/// - tangent: with the rotations held at their poses at s the pair only translates, so its gap
///   along n changes at n . v exactly; each point p strays from its held-rotation path by at most
///   theta reach(p) per unit time (the chord of its arc about its model's axis, ccd::Spin), so the
///   gap falls at most at rate = min(cap, -n . v + theta_a rho_a + theta_b rho_b), rho the largest
///   reach of the set, cap = speed + the same turning terms; step gap / rate;
/// - directional: a point p of A turning about A's axis k moves along n at theta |p . (u x k)|
///   with u = n in A's turning frame, and u turns about k, so over a time tau that lever grows by
///   at most theta tau reach(p); likewise for B: the gap falls by at most tau r1 + tau^2 r2 / 2,
///   r1 = -n . v + theta_a lever_a + theta_b lever_b, r2 = theta_a^2 rho_a + theta_b^2 rho_b
///   (lever: the largest |p . (u x k)| over the set): the step is that polynomial's root. A
///   roller or wheel spinning about its own axis moves its contact point along the normal
///   hardly at all, which the tangent step cannot see.
/// The gap along a fixed direction is a lower bound of the distance of two convex sets, so the
/// pair stays apart while it stays positive. n_error enters every term that n multiplies.
ANTCD_API Scalar pair_step(Scalar gap, const Vec3& n, Scalar n_error, const Vec3& v,
                           const Mat3& b_to_a, const RigidPair& m, std::span<const Vec3> a_points,
                           std::span<const Vec3> b_points);

}  // namespace antcd::ccd
