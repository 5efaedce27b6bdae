// Private: the surface distance query of antcd/distance.hpp started from a known triangle pair,
// for callers that query the same two models again and again at nearby poses (the sweep's
// conservative advancement, src/ccd/sweep.cpp).
//
// The seed is a triangle pair's distance at the query's poses: an upper bound of the minimum from
// the start, so the branch-and-bound prunes with it before it has reached any leaf. The answer
// keeps every guarantee of distance() for the same request (distance is a pair's distance,
// lower_bound is proven, the tolerance and the upper bound mean the same); only the pair reported
// may be the seed's. Unsigned distance only.
// Thread safety: as distance(); the seed is read only.
#pragma once

#include <antcd/distance.hpp>
#include <antcd/export.hpp>
#include <antcd/geometry.hpp>

#include <cstdint>
#include <limits>

namespace antcd::detail {

struct DistanceSeed {
  /// The pair's distance at the query's poses; a seed that is not positive and finite is ignored.
  Scalar distance = std::numeric_limits<Scalar>::infinity();
  Vec3 point_a = Vec3::Zero();   // world frame, on triangle_a of A
  Vec3 point_b = Vec3::Zero();   // world frame, on triangle_b of B
  std::uint32_t triangle_a = 0;  // mesh indices
  std::uint32_t triangle_b = 0;
};

/// The seed of triangle ta of A and tb of B, whose distance at the query's poses is `d` (world
/// frame).
inline DistanceSeed make_seed(const geometry::TriangleDistance& d, std::uint32_t ta,
                              std::uint32_t tb) {
  DistanceSeed seed;
  seed.distance = d.distance;
  seed.point_a = d.pa;
  seed.point_b = d.pb;
  seed.triangle_a = ta;
  seed.triangle_b = tb;
  return seed;
}

/// The pair a query at the same poses reported (ignored unless its distance is positive).
inline DistanceSeed make_seed(const DistanceResult& r) {
  return make_seed({r.distance, r.point_a, r.point_b}, r.triangle_a, r.triangle_b);
}

/// distance(a, pose_a, b, pose_b, request) started from `seed` (request.signed_distance must be
/// false: an ArgumentError otherwise).
ANTCD_API DistanceResult seeded_distance(const Model& a, const Transform& pose_a, const Model& b,
                                         const Transform& pose_b, const DistanceRequest& request,
                                         const DistanceSeed& seed);

}  // namespace antcd::detail
