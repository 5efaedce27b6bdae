// antcd/sweep.hpp — continuous collision detection between two rigidly moving meshes.
//
// Definitions (see antcd/ccd.hpp for the motion): model A moves from pose_a0 at t = 0 to pose_a1
// at t = 1, B from pose_b0 to pose_b1, each with its translation interpolated linearly and its
// rotation at constant angular velocity about its model origin (ccd::interpolate_pose). Both
// surfaces are closed sets of non-degenerate triangles, as in collide() and distance(). The time
// of impact t* is the first t in [0, 1] at which the surfaces are within min_separation.
//
// Method: conservative advancement on the Sphere-OBB hierarchy. At time t, distance() (the
// hierarchy's branch-and-bound, certified lower bounds) gives a lower bound L of the distance;
// no point of either surface moves relative to the other faster than
//   mu = |(T_a1 - T_a0) - (T_b1 - T_b0)| + theta_a r_a + theta_b r_b,
// theta the rotation angle of a motion and r the largest distance of the model's points from its
// turning axis: the slerp turns the model about one axis k fixed in the model frame through its
// origin, so a point p runs on a circle of radius rho(p) = |k x p| at theta rho(p) per unit time
// (a roller or wheel spinning about its own axis moves its rim, not its far ends). r is bounded
// by the hierarchy's root sphere (rho(centre) + radius) or its root box's corners, whichever is
// less; the computed axis's rounding is allowed for, and a turn under 2e-9 rad uses |p|. So the
// surfaces stay more than min_separation apart until t + (L - min_separation) / mu and the search
// advances there. A rounding allowance (1e-12 of the scene's size: coordinates, radii,
// translations) is taken off every L, covering the rounding of the interpolated poses, of the
// distance and of t.
// Contact at the start first: surfaces that intersect at t = 0 (collide()'s exact boolean test at
// the start poses) have toi 0, proven, with that intersecting pair as the contact; a resting
// contact costs one discrete test.
// Then interval proofs: an earliest-first bisection of [0, 1] (pieces down to 1/16) tests each
// piece with one bounded boolean traversal at its midpoint pose, where a node pair is apart over
// the piece if its spheres at the midpoint are farther apart than min_separation plus their
// centres' motion bound over half the piece (|relative translation| + theta rho(centre) per node:
// a ball turns into itself about its centre), or its boxes are, with each box's own turn about
// its centre added (theta times the node's radius, or its half extents times the sines of their
// angles to the axis where less: a long node along the axis hardly turns), or its sphere centres'
// chords between the piece's end poses stay farther apart than the radii plus the chords' bend
// (rho(centre) theta^2 w^2 / 8, w the width), or its boxes, each kept at its midpoint orientation
// and swept along that chord, are separated on a face axis with that margin; triangle pairs
// likewise (the gaps along both normals or the exact distance at the midpoint, or balls about the
// centroids along their chords). A motion whose pieces are all apart is a miss; otherwise the
// advancement starts at the first piece not proven apart.
// Each distance query of the advancement starts from the previous query's closest triangle pair,
// evaluated exactly at the new pose (an upper bound that prunes from the first node pair; the
// lower bound it returns is certified as before).
// Convex pairs (both models convex, as penetration.hpp detects it, once per Model): after a costly
// distance query the step is also tried across the plane through the closest points, held while
// the two vertex sets stay on their sides of it (their hulls are the surfaces): for a vertex of
// each, its projection on the plane's normal is linear plus a sinusoid in t, within
// (theta_a^2 rho_a + theta_b^2 rho_b) w^2 / 8 of its chord over a width w, so the least gap of the
// two ends less that, above min_separation, proves the width; a sweep stops trying after two
// steps it did not lengthen.
// Fine meshes near contact (a query that examined 400 node pairs or more, with a gap below four
// typical triangle sizes, root radius * sqrt(4 pi / triangles)): the advancement hands over to one
// traversal of both hierarchies in which every node pair and every triangle pair advances in time
// on its own, earliest first. A node pair advances while its spheres are apart (its centres'
// step, below), or while its boxes are apart on a separating axis, by that gap over the pair's
// own motion bound; then its children are examined from the time it reached. A triangle pair
// advances on its planes and centroid axis, then on its exact distance. Each step from time s
// keeps the pair's gap along one direction n positive (n: the closest-point direction, or the
// axis used; a gap along a fixed direction is a lower bound of the distance), the longer of two
// proofs: the tangent (rotations held at s, the pair translates and its gap along n changes at
// n . v; each point strays from that path by at most theta rho(p) per unit time) and the
// directional one (a point of A moves along n by the turn at theta |p . (u x k)|, u = n in A's
// turning frame, a lever that grows by at most theta rho(p) per unit time as u turns; likewise
// for B: over a time tau the gap falls by at most tau r1 + tau^2 r2 / 2 with r1 = -n . v + theta_a
// lever_a + theta_b lever_b and r2 = theta_a^2 rho_a + theta_b^2 rho_b, largest over each set's
// corners). Chord tests let a pair jump 8 such steps at once: in A's frame a point of B runs
// within w^2 / 8 (theta_a^2 qa + 2 theta_a (theta_b yb + |v|) + theta_b^2 yb) of its chord over
// a width w (qa the distance of its position in A's frame from A's axis, grown by w times its
// speed; yb that of its position in B's frame from B's axis), so spheres whose centre chord stays
// apart by more than that, and triangles whose B corners stay below a separating plane at both ends
// by more than that, stay apart over the whole width; a triangle pair whose gap closes at the far
// end is tried once more over 0.95 of the width at which its two ends' gaps, interpolated, close
// (a pair nearing its contact then reaches it in a few steps, not in ever shorter ones). The first
// triangle pair found within
// min_separation + allowance + mu * time_tolerance / 2 gives toi: every other pair is proven apart
// until a later time. A traversal that examines 20 000 pairs (a later one of the same sweep twice
// as many as the last) hands back the time it reached, and the whole-mesh advancement goes on from
// there.
//
// Guarantees
// - Conservative: if the surfaces come within min_separation at some t in [0, 1], the result is a
//   hit with toi <= t*. A miss is a proof that they never do.
// - A hit is proven (tolerance_decided false) when at toi the exact test finds the surfaces
//   intersecting or a triangle pair's distance computed at toi is within min_separation less the
//   allowance. Otherwise the surfaces are at toi within min_separation + mu * time_tolerance +
//   allowance (result.distance is a pair's distance there): the search stops only that close, and
//   a step from any farther reaches at least time_tolerance / 2 ahead.
// - After max_iterations iterations (the test at the start, interval tests, distance queries and
//   traversals) the search stops with a hit at the time reached (tolerance_decided and
//   budget_exhausted set): still toi <= t*.
// - contact: a triangle pair at toi whose distance is within mu * time_tolerance / 2 + allowance
//   of the minimum (an intersecting pair when the surfaces intersect), world frame: point is the
//   common point or the closest points' midpoint, normal and depth as in collide.hpp (from B
//   towards A).
//
// Thread safety: sweep() only reads its Models; any number of threads may sweep the same Models.
// Errors: ArgumentError for min_separation < 0 or not finite, time_tolerance <= 0 or not finite,
// max_iterations == 0, a pose with a non-finite entry or a rotation that is not orthonormal
// (|R^T R - I| > 1e-6) with determinant +1, a translation entry, min_separation or a model's
// reach from its origin beyond kSweepCoordinateRange (below); the message names the argument.
// A time_tolerance above 1 acts as 1 (the whole motion).
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/export.hpp>

#include <cstdint>

namespace antcd {

/// The coordinate range of continuous queries between meshes (sweep(), World::sweep_poses and
/// World::set_poses_continuous, and the CLI, Python and WebAssembly sweeps over them): every
/// translation entry of their poses, min_separation and each model's reach from its origin (root
/// centre + radius) must be at most this in magnitude; larger ones are refused with an
/// ArgumentError naming the argument. Why 1e100: the certified bounds square and multiply
/// differences of posed coordinates (a distance is the root of a sum of squares, an orientation a
/// product of three differences): (2 sqrt(3) 1e100)^3 = 4e301 stays below DBL_MAX (1.8e308) with
/// room for the few terms summed, where at 1e155 squared distances became +inf and a sweep
/// through a contact answered a proven miss. (The primitives, ccd::vertex_face and edge_edge,
/// need no range: their bounds stay conservative for any finite input, see docs/ccd.md.)
inline constexpr Scalar kSweepCoordinateRange = 1e100;

struct SweepRequest {
  /// Contact distance (mesh units, >= 0).
  Scalar min_separation = 0;
  /// Time tolerance (> 0), see the guarantees above.
  Scalar time_tolerance = 1e-6;
  /// Largest number of iterations: the test at the start, interval tests, distance queries and
  /// traversals (>= 1).
  std::uint32_t max_iterations = 100000;
};

struct SweepResult {
  bool hit = false;
  /// Time of impact in [0, 1] when hit (1 otherwise).
  Scalar toi = 1;
  /// The contact at toi (when hit): triangles, world point, distance, normal and depth.
  Contact contact;
  /// The hit rests on the tolerance, not on a proof (see the header comment).
  bool tolerance_decided = false;
  /// max_iterations ran out (the hit is then a conservative stop).
  bool budget_exhausted = false;
  /// When hit: the contact pair's distance at toi (within mu * time_tolerance / 2 + allowance
  /// above the surfaces' distance); else a proven lower bound of the distance at the
  /// last time examined (>= min_separation; when interval tests proved the motion apart, of the
  /// distance over the whole motion; equal to min_separation where a box test or the traversal,
  /// which measure no gap over the motion, proved the miss).
  Scalar distance = 0;
  /// mu: the bound on the relative speed of the surfaces (mesh units per unit time).
  Scalar motion_bound = 0;
  /// Iterations made: the test at the start, interval tests, distance queries and traversals.
  std::uint32_t iterations = 0;
};

/// Continuous collision query between A moving from pose_a0 to pose_a1 and B moving from pose_b0
/// to pose_b1 over t in [0, 1].
ANTCD_API SweepResult sweep(const Model& a, const Transform& pose_a0, const Transform& pose_a1,
                            const Model& b, const Transform& pose_b0, const Transform& pose_b1,
                            const SweepRequest& request = {});

}  // namespace antcd
