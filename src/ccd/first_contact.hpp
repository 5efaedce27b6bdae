// Private: the earliest contact of two rigidly moving models by one traversal of both hierarchies
// in which every node pair and every triangle pair advances in time on its own (conservative
// advancement per pair, after Tang, Kim and Manocha's C2A, 2009). Used by the mesh sweep
// (sweep.cpp) after its interval proofs.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include <cstdint>

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
/// A pair of nodes, or of triangles, at distance d (lower bound) at time t stays apart until
/// t + (d - separation) / rate, where rate bounds how fast its distance may fall: for the node
/// spheres |relative translation| + theta_a |centre_a| + theta_b |centre_b| (a ball turns into
/// itself about its centre, so only the centres' paths count), for their boxes the same with each
/// |centre| + radius, for a triangle pair pair_rate() below. Pairs are examined earliest first
/// (a heap); each advances from its parent's time in steps of that size until it may touch (then
/// its children are examined from there) or passes 1 (then it is dropped). Chord tests
/// (first_contact.cpp, nodes() and triangles()) let a pair jump several steps at once where the
/// paths, in A's frame, stay near their chords. The first triangle pair examined whose exact
/// distance is within separation + allowance + stop_gap, or which the exact test finds
/// intersecting, gives the result: every pair still queued is proven apart until its own later
/// time, so no pair is within separation before toi.
/// Rounding: `allowance` (scene's size times kArithmetic) is taken off every triangle distance and
/// `volume` (kVolume of the scene's size) off every node distance, as in the sweep.
/// Exported for the tests (tests/ccd/first_contact_test.cpp). Thread safety: reads its models only.
ANTCD_API FirstContact first_contact(const RigidPair& m, Scalar t0, Scalar separation,
                                     Scalar allowance, Scalar volume, Scalar stop_gap,
                                     const FirstContactLimits& limits = {});

/// How fast the distance `d` of two triangles may fall from time s on: d at s (closest points pa
/// of A's triangle and pb of B's, both in one frame), `v` the relative translation velocity of A
/// against B in that frame, `turning` >= theta_a rho_a + theta_b rho_b (rho the triangle's largest
/// vertex norm in its model's frame), `cap` a rate that always holds. With the rotations held at
/// their poses at s, the pair only translates, along a line: the distance of two convex sets whose
/// offset moves along a line is convex in time, so it stays above its tangent at s, of slope
/// n . v (n the unit vector from pb to pa). Each point p of A strays from its held-rotation path by
/// at most theta_a |p| per unit time (the chord of its arc about the model origin), and likewise
/// for B: the distance falls by at most turning - n . v per unit time (negative: it never falls).
/// n's direction is allowed an error of 2 allowance / d; pairs nearer than 4 allowance get `cap`.
ANTCD_API Scalar pair_rate(Scalar d, const Vec3& pa, const Vec3& pb, const Vec3& v, Scalar turning,
                           Scalar cap, Scalar allowance);

}  // namespace antcd::ccd
