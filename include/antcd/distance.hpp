// antcd/distance.hpp — minimum distance between two posed meshes, with closest points.
//
// Definition
// - The distance of models A and B at poses pose_a, pose_b is the minimum Euclidean distance
//   between their SURFACES (the union of their non-degenerate triangles, each a closed set):
//   min over triangle pairs (s, t) of min |p - q|, p in s, q in t. Whether the surfaces share a
//   point is decided exactly (DistanceResult::intersecting, the same predicate as collide() with
//   delta 0); the distance is then 0. Surfaces apart by less than the rounding of the distance
//   computation (about 1e-16 of the coordinates) may report distance 0 with intersecting false.
//   A mesh wholly inside another is at a positive distance: this is a surface query.
// - Frames: each Model's geometry is in its own frame; poses map it to the world. The closest
//   points are in WORLD coordinates; triangle indices are indices into each Model's mesh.
// - Units: mesh units; distances are never negative (no penetration depth here). The signed
//   distance of two solids, negative when they overlap, is antcd::signed_distance
//   (antcd/penetration.hpp), which composes this query with the penetration depth.
//
// Accuracy
// - Exact mode (no tolerance): the triangle pair reported is a pair of minimum distance up to the
//   rounding of the triangle–triangle distance (a few ulps of the coordinates' magnitude, see
//   docs/guarantees.md); the branch-and-bound never prunes a node pair that could hold a closer
//   pair (its lower bounds are widened by a rounding allowance).
// - With a tolerance (abs_tolerance > 0 or rel_tolerance > 0) the search may stop early: the
//   answer then satisfies   true distance >= distance - max(abs_tolerance, rel_tolerance *
//   distance) and DistanceResult::approximate says whether a pair was actually skipped on that
//   ground. lower_bound is always a proven lower bound of the true distance.
// - With an upper bound, the search stops once the distance is known to exceed it; the answer
//   then says so (beyond_upper_bound) and only lower_bound (> upper_bound) is a guarantee.
//
// Thread safety: distance() only reads its Models; any number of threads may query the same
// Models concurrently.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/error.hpp>
#include <antcd/export.hpp>

#include <cstdint>
#include <limits>

namespace antcd {

struct DistanceRequest {
  /// Stop once the distance is known to be larger than this (mesh units, >= 0; +inf: no bound).
  Scalar upper_bound = std::numeric_limits<Scalar>::infinity();
  /// Accept an answer within max(abs_tolerance, rel_tolerance * distance) above the true distance.
  /// abs_tolerance >= 0, 0 <= rel_tolerance < 1. Both 0 (default): exact search.
  Scalar abs_tolerance = 0;
  Scalar rel_tolerance = 0;
};

struct DistanceResult {
  /// The minimum distance (see the header comment). When beyond_upper_bound, the distance of the
  /// closest pair seen (possibly +inf when none was examined), not a minimum.
  Scalar distance = std::numeric_limits<Scalar>::infinity();
  /// A proven lower bound of the true minimum distance (== distance for an exact answer).
  Scalar lower_bound = 0;
  /// Closest points, world frame: point_a on triangle_a of A, point_b on triangle_b of B, with
  /// |point_a - point_b| == distance (up to rounding). When the surfaces meet, point_a == point_b
  /// is a common point. Meaningless when distance is +inf.
  Vec3 point_a = Vec3::Zero();
  Vec3 point_b = Vec3::Zero();
  std::uint32_t triangle_a = 0;
  std::uint32_t triangle_b = 0;
  /// The surfaces share a point (exact decision; distance is then 0).
  bool intersecting = false;
  /// A tolerance of the request let the search skip a node or triangle pair that might have been
  /// closer (by less than the tolerance).
  bool approximate = false;
  /// The true distance is larger than request.upper_bound (lower_bound > upper_bound).
  bool beyond_upper_bound = false;
  std::uint64_t node_pairs = 0;      ///< node pairs whose lower bound was examined
  std::uint64_t triangle_tests = 0;  ///< exact triangle–triangle distances computed
};

/// Minimum distance between the surfaces of two posed models. Throws ArgumentError when a request
/// field is out of range (negative or NaN bound or tolerance, rel_tolerance >= 1).
ANTCD_API DistanceResult distance(const Model& a, const Transform& pose_a, const Model& b,
                                  const Transform& pose_b, const DistanceRequest& request = {});

}  // namespace antcd
