// Mesh–mesh sweep by conservative advancement on the hierarchy's distance query; see
// antcd/sweep.hpp for the motion bound and the guarantees.
#include <antcd/ccd.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/geometry.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ccd/motion.hpp"
#include "util/check.hpp"
#include "util/pose_check.hpp"

namespace antcd {
namespace {

/// The loop's distance queries may stop within this fraction of the distance (the lower bound is
/// still proven); only the stopping decision needs the exact distance.
constexpr Scalar kStepRelTolerance = 0.5;

void check_pose(const Transform& p, const char* name) {
  Scalar err = 0;
  if (const char* problem = detail::pose_problem(p, err)) {
    throw ArgumentError(std::string("sweep: ") + name + " " + problem);
  }
}

/// The larger of the two lower bounds distance() proves: its lower_bound, and its distance less
/// the tolerance it was allowed (`slack`).
Scalar proven_lower_bound(const DistanceResult& d, Scalar slack) {
  return std::isfinite(d.distance) ? std::max(d.lower_bound, d.distance - slack) : d.lower_bound;
}

void fill_contact(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                  const DistanceResult& d, Contact& c) {
  c.triangle_a = d.triangle_a;
  c.triangle_b = d.triangle_b;
  c.point = (d.point_a + d.point_b) / 2;
  c.distance = d.distance;
  const auto& ta = a.mesh().triangles[d.triangle_a];
  const auto& tb = b.mesh().triangles[d.triangle_b];
  const auto& va = a.mesh().vertices;
  const auto& vb = b.mesh().vertices;
  const geometry::TrianglePenetration pen =
      geometry::triangle_penetration(pa.apply(va[ta[0]]), pa.apply(va[ta[1]]), pa.apply(va[ta[2]]),
                                     pb.apply(vb[tb[0]]), pb.apply(vb[tb[1]]), pb.apply(vb[tb[2]]));
  c.normal = pen.normal;
  c.depth = pen.depth;
}

}  // namespace

SweepResult sweep(const Model& a, const Transform& pose_a0, const Transform& pose_a1,
                  const Model& b, const Transform& pose_b0, const Transform& pose_b1,
                  const SweepRequest& request) {
  check_pose(pose_a0, "pose_a0");
  check_pose(pose_a1, "pose_a1");
  check_pose(pose_b0, "pose_b0");
  check_pose(pose_b1, "pose_b1");
  const Scalar ms = request.min_separation;
  const Scalar tol = request.time_tolerance;
  detail::require_non_negative("sweep", "min_separation", ms);
  detail::require_positive("sweep", "time_tolerance", tol);
  detail::require_at_least("sweep", "max_iterations", request.max_iterations, 1);

  const Scalar ra = ccd::origin_radius(a);
  const Scalar rb = ccd::origin_radius(b);
  const Vec3 relative_move =
      (pose_a1.translation - pose_a0.translation) - (pose_b1.translation - pose_b0.translation);
  const Scalar mu = tolerance::widened(
      relative_move.norm() + ccd::rotation_angle(pose_a0.rotation, pose_a1.rotation) * ra +
      ccd::rotation_angle(pose_b0.rotation, pose_b1.rotation) * rb);
  const Scalar scale = ra + rb + ms + pose_a0.translation.norm() + pose_a1.translation.norm() +
                       pose_b0.translation.norm() + pose_b1.translation.norm();
  // The poses, the distance and the time steps are each within a few 1e-16 of the scene's size
  // (see sweep.hpp).
  const Scalar allowance = tolerance::kArithmetic * scale;

  SweepResult result;
  result.motion_bound = mu;
  Scalar t = 0;
  while (true) {
    if (result.iterations >= request.max_iterations) {
      result.hit = true;
      result.toi = t;
      result.tolerance_decided = true;
      result.budget_exhausted = true;
      break;
    }
    const Transform pa = ccd::interpolate_pose(pose_a0, pose_a1, t);
    const Transform pb = ccd::interpolate_pose(pose_b0, pose_b1, t);
    // Free for the rest of the motion once the distance exceeds what mu can close by t = 1.
    DistanceRequest step;
    step.rel_tolerance = kStepRelTolerance;
    step.upper_bound = ms + allowance + mu * (1 - t);
    DistanceResult d = distance(a, pa, b, pb, step);
    ++result.iterations;
    if (d.beyond_upper_bound) {
      result.distance = d.lower_bound;
      break;
    }
    // distance() promises both its lower bound and distance * (1 - rel_tolerance).
    Scalar gap = proven_lower_bound(d, kStepRelTolerance * d.distance) - ms - allowance;
    if (gap <= mu * tol || d.intersecting) {
      // Near enough to stop: decide on a distance within mu * tol / 2 of the minimum (an exact
      // one costs far more where many pairs are about equally close, e.g. a ball in a ring).
      // d.distance is a pair's distance (>= the minimum) and the minimum is at most mu * tol / 2
      // below it, so a stop here is within reach and a step from here is >= tol / 2.
      DistanceRequest settle;
      settle.abs_tolerance = mu * tol / 2;
      d = distance(a, pa, b, pb, settle);
      ++result.iterations;
      const bool proven = d.intersecting || d.distance + allowance <= ms;
      if (proven || d.distance - ms - allowance <= mu * tol) {
        result.hit = true;
        result.toi = t;
        result.tolerance_decided = !proven;
        result.distance = d.distance;
        fill_contact(a, pa, b, pb, d, result.contact);
        break;
      }
      gap = proven_lower_bound(d, settle.abs_tolerance) - ms - allowance;
    }
    // No contact before t + gap / mu (rounded down; the allowance covers the sum's rounding).
    const Scalar advance = gap / mu * (1 - 1e-15);
    if (!(t + advance < 1)) {
      result.distance = d.lower_bound;
      break;
    }
    t += advance;
  }
  return result;
}

}  // namespace antcd
