// signed_distance() (antcd/penetration.hpp): the surface distance of two closed models composed
// with their penetration depth when the solids overlap.
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/penetration.hpp>

#include "points/point_index.hpp"

#include <string>

namespace antcd {

namespace {

// One of two closed models whose surfaces are apart lies inside the other: a vertex of one is
// inside the other (then all are).
bool nested(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b) {
  const Vec3 a_in_b = pose_b.inverse().apply(pose_a.apply(a.leaf_corners()(0, 0)));
  const Vec3 b_in_a = pose_a.inverse().apply(pose_b.apply(b.leaf_corners()(0, 0)));
  return detail::inside_solid(b, a_in_b) || detail::inside_solid(a, b_in_a);
}

}  // namespace

DistanceResult signed_distance(const Model& a, const Transform& pose_a, const Model& b,
                               const Transform& pose_b, const DistanceRequest& request) {
  for (const Model* m : {&a, &b}) {
    if (!m->is_closed()) {
      throw ArgumentError("signed_distance: model '" + m->source() +
                          "' is not closed, so it bounds no solid");
    }
  }
  DistanceResult result = distance(a, pose_a, b, pose_b, request);
  if (!result.intersecting && !nested(a, pose_a, b, pose_b)) return result;
  PenetrationRequest pr;
  if (request.abs_tolerance > 0 || request.rel_tolerance > 0) {
    pr.abs_tolerance = request.abs_tolerance;
    pr.rel_tolerance = request.rel_tolerance;
  }
  const PenetrationResult pd = penetration(a, pose_a, b, pose_b, pr);
  if (!pd.overlapping) return result;  // touching: distance 0
  result.distance = -pd.upper;
  result.lower_bound = -pd.upper;
  result.approximate = !pd.exact;
  result.beyond_upper_bound = false;
  result.point_a = pd.point_a;
  result.point_b = pd.point_b;
  return result;
}

}  // namespace antcd
