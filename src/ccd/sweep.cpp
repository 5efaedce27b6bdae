// Mesh–mesh sweep by conservative advancement on the hierarchy's distance query; see
// antcd/sweep.hpp for the motion bound and the guarantees.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/geometry.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <antcd/pose.hpp>
#include "ccd/first_contact.hpp"
#include "ccd/motion.hpp"
#include "ccd/plane_step.hpp"
#include "ccd/swept_proximity.hpp"
#include "distance/seeded.hpp"
#include "penetration/convex.hpp"
#include "util/check.hpp"

namespace antcd {
namespace {

/// The loop's distance queries may stop within this fraction of the distance (the lower bound is
/// still proven); only the stopping decision needs the exact distance. With the queries seeded by
/// the last closest pair (see seed_at), proving more of the distance pays: callgrind on the
/// 12-frame production line of seed 3, 0.5 / 0.3 / 0.15 / 0.05 / 0 (exact): 7.19 / 6.49 / 6.19
/// / 6.26 / 9.55 G instructions (unseeded, 0.5: 8.45 G).
constexpr Scalar kStepRelTolerance = 0.15;
/// The whole-mesh advancement hands over to ccd::first_contact (every node pair and triangle pair
/// advancing on its own) after a distance query that examined at least this many node pairs:
/// fine meshes near each other, where each further query opens hundreds of node pairs again
/// (below, on small meshes such as the thin sheets of bench/ccd_bench, the whole-mesh queries cost
/// less: 50-300 node pairs, 6-30 us a query).
constexpr std::uint64_t kTraversalNodePairs = 400;
/// ... and only once the gap is below this many typical triangle sizes (see triangle_size in
/// sweep()): farther away, the pairs within reach of the next steps are too many for advancing
/// each on its own. Callgrind, bench torus/sphere sweeps / 12-frame production line / a 60-frame
/// continuous scene of 40 assimp meshes (spiders, Wuson, sphereWithHole, box; `scene generate
/// --mesh`, seed 5): no limit 38.0 M / 1.73 G / 6.89 G; 8: 38.1 M / 1.73 G / 6.64 G; 4: 38.7 M /
/// 1.73 G / 6.52 G; 2: 39.9 M / 1.73 G / 6.50 G; 0.5: 42.1 M / 1.75 G / 6.60 G; no traversal at
/// all: 80.2 M / 7.26 G / 6.77 G (main at 4c8b036, with the endgame windows: 54.0 M / 5.22 G /
/// 6.35 G).
constexpr Scalar kTraversalGap = 4;
/// Pairs the first traversal of a sweep may examine (each later one twice the last, up to the
/// second figure). Random fast motions of assimp's spiders, Wuson and sphereWithHole, a fine torus
/// and a sheet (300 motions each of two seeds, against 1000-step sub-stepping; a driver outside
/// the tree): 200 000 at once: 592 / 386 ms in all, four sweeps of about 60 ms (a long graze, then
/// the whole-mesh advancement from the start); 20 000, resuming from the time reached: 311 / 287
/// ms (main at 4c8b036, before the traversal: 404 / 405 ms); with kTraversalGap too: 359 / 304
/// ms (4c8b036 in the same run: 394 / 397 ms).
constexpr std::uint64_t kTraversalPairs = 20000;
constexpr std::uint64_t kMaxTraversalPairs = 1 << 20;
/// Depth of the earliest-first bisection that proves stretches of the motion apart before the
/// advancement starts (pieces down to 2^-depth of the motion).
/// Scene production line (`antcd scene generate --frames 60 --seed 3`): depth 3 / 4 / 6 settle
/// 5893 / 5919 / 5956 of 8473 sweeps this way. With the traversal (ccd::first_contact), callgrind
/// on its 12-frame run (`run --continuous --threads 1`) / bench/ccd_bench's torus-sphere and
/// thin-sheet motions, before the chord tests: depth 3: 3.85 G / 34.2 M / 5.38 M; 4: 3.66 G /
/// 32.1 M / 5.24 M; 5: 3.30 G / 32.8 M / 5.38 M; 6: 3.09 G / 32.6 M / 6.29 M; 8: 3.17 G / 34.9 M
/// / 7.97 M. With the chord tests and the resumable budget, depth 4 / 5: 1.73 / 1.83 G on the
/// production line and 6.89 / 7.71 G on the 60-frame assimp scene (see kTraversalGap).
constexpr int kBisectDepth = 4;
/// Steps in a row that ccd::plane_step did not lengthen before a sweep of a convex pair stops
/// trying it (see the loop).
constexpr int kPlaneMisses = 2;
/// ... and tries it only after a distance query that examined at least (vertices of both models)
/// / this many node pairs: a step scans every vertex up to four times, about what a query of that
/// many node pairs costs.
constexpr std::size_t kPlanePairsPerVertex = 12;
/// Node pairs one interval test may examine before giving up: a piece that is apart but close
/// costs a whole proximity traversal (7 000-15 000 node pairs seen without a cap, more than the
/// advancement it saves). 300 settled 5888 sweeps, 1000 settled 5919 and was faster.
constexpr std::uint32_t kApartBudget = 1000;

void require_rigid(const Transform& p, const char* name) {
  if (const PoseCheck c = check_pose(p); !c.rigid()) {
    throw ArgumentError(std::string("sweep: ") + name + " " + c.problem());
  }
  ccd::require_sweep_translation("sweep", name, p);
}

/// The larger of the two lower bounds distance() proves: its lower_bound, and its distance less
/// the tolerance it was allowed (`slack`).
Scalar proven_lower_bound(const DistanceResult& d, Scalar slack) {
  return std::isfinite(d.distance) ? std::max(d.lower_bound, d.distance - slack) : d.lower_bound;
}

/// Triangle `i` of the model's mesh at pose `p` (world frame).
std::array<Vec3, 3> posed_triangle(const Model& m, const Transform& p, std::uint32_t i) {
  const auto& t = m.mesh().triangles[i];
  const auto& v = m.mesh().vertices;
  return {p.apply(v[t[0]]), p.apply(v[t[1]]), p.apply(v[t[2]])};
}

/// The triangle pair (ta, tb) at the poses pa, pb as a seed of the next distance query: its
/// distance there bounds the minimum from above.
detail::DistanceSeed seed_at(const Model& a, const Transform& pa, const Model& b,
                             const Transform& pb, std::uint32_t ta, std::uint32_t tb) {
  const auto x = posed_triangle(a, pa, ta);
  const auto y = posed_triangle(b, pb, tb);
  return detail::make_seed(geometry::triangle_distance(x[0], x[1], x[2], y[0], y[1], y[2]), ta, tb);
}

/// The contact of triangle ta of A and tb of B at the poses pa, pb (world frame).
void fill_contact(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                  std::uint32_t ta, std::uint32_t tb, Contact& c) {
  c.triangle_a = ta;
  c.triangle_b = tb;
  const auto x = posed_triangle(a, pa, ta);
  const auto y = posed_triangle(b, pb, tb);
  const geometry::TriangleDistance d =
      geometry::triangle_distance(x[0], x[1], x[2], y[0], y[1], y[2]);
  c.point = (d.pa + d.pb) / 2;
  c.distance = d.distance;
  const geometry::TrianglePenetration pen =
      geometry::triangle_penetration(x[0], x[1], x[2], y[0], y[1], y[2]);
  c.normal = pen.normal;
  c.depth = pen.depth;
}

/// Earliest-first bisection of [t, 1] with ccd::interval_apart, down to intervals of width
/// (1 - t) / 2^depth: returns the start of the earliest such interval not proven apart (nothing
/// touches before it), or 1 when every piece of [t, 1] is proven apart (the models then stay at
/// least separation + slack apart, see interval_apart). Counts its tests in `tests`.
Scalar apart_until(const ccd::RigidPair& m, Scalar t, Scalar separation, int depth,
                   std::uint32_t& tests, Scalar& slack) {
  struct Piece {
    Scalar lo, hi;
    int depth;
  };
  std::array<Piece, 64> stack;
  std::size_t top = 0;
  stack[top++] = {t, 1, 0};
  while (top > 0) {
    const Piece p = stack[--top];
    ++tests;
    if (ccd::interval_apart(m, p.lo, p.hi, separation, kApartBudget, &slack)) continue;
    if (p.depth >= depth) return p.lo;
    const Scalar mid = (p.lo + p.hi) / 2;
    stack[top++] = {mid, p.hi, p.depth + 1};
    stack[top++] = {p.lo, mid, p.depth + 1};
  }
  return 1;
}

}  // namespace

SweepResult sweep(const Model& a, const Transform& pose_a0, const Transform& pose_a1,
                  const Model& b, const Transform& pose_b0, const Transform& pose_b1,
                  const SweepRequest& request) {
  require_rigid(pose_a0, "pose_a0");
  require_rigid(pose_a1, "pose_a1");
  require_rigid(pose_b0, "pose_b0");
  require_rigid(pose_b1, "pose_b1");
  const Scalar ms = request.min_separation;
  detail::require_non_negative("sweep", "min_separation", ms);
  ccd::require_sweep_range("sweep", "min_separation", "", ms);
  detail::require_positive("sweep", "time_tolerance", request.time_tolerance);
  detail::require_at_least("sweep", "max_iterations", request.max_iterations, 1);
  // A window wider than the whole motion decides nothing more than the whole motion (and mu times
  // a huge tolerance would overflow).
  const Scalar tol = std::min(request.time_tolerance, Scalar{1});

  const Scalar ra = ccd::origin_radius(a);
  const Scalar rb = ccd::origin_radius(b);
  // A model beyond the range (or with a non-finite root volume: vertices beyond float's range).
  ccd::require_sweep_range("sweep", "model a", "reach from its origin", ra);
  ccd::require_sweep_range("sweep", "model b", "reach from its origin", rb);
  const ccd::RigidPair motion = ccd::rigid_pair(a, pose_a0, pose_a1, b, pose_b0, pose_b1);
  const Scalar mu = ccd::motion_bound(motion);
  const Scalar scale = ra + rb + ms + pose_a0.translation.norm() + pose_a1.translation.norm() +
                       pose_b0.translation.norm() + pose_b1.translation.norm();
  // The poses, the distance and the time steps are each within a few 1e-16 of the scene's size
  // (see sweep.hpp).
  const Scalar allowance = tolerance::kArithmetic * scale;

  SweepResult result;
  result.motion_bound = mu;
  // Surfaces that intersect at t = 0 (resting contact: most hits of a continuous scene frame)
  // have toi 0, proven by one exact boolean test, before any interval proof (those would all
  // fail on the pieces that start at 0). The result is reused per thread so that the query does
  // not allocate.
  {
    thread_local CollisionResult start;
    ++result.iterations;
    if (collide(a, pose_a0, b, pose_b0, CollisionRequest{}, start)) {  // delta 0: exact
      result.hit = true;
      result.toi = 0;
      fill_contact(a, pose_a0, b, pose_b0, start.contacts.front().triangle_a,
                   start.contacts.front().triangle_b, result.contact);
      result.distance = result.contact.distance;
      return result;
    }
  }
  // Whole stretches of the motion proven apart at once (most swept pairs of a scene never touch).
  Scalar slack = std::numeric_limits<Scalar>::infinity();
  Scalar t = apart_until(motion, 0, ms + allowance, kBisectDepth, result.iterations, slack);
  if (t >= 1) {
    result.distance = ms + slack;
    return result;
  }
  // Both models convex (penetration/convex.hpp, derived once per Model): their surfaces are their
  // hulls' boundaries, so a plane between the vertex sets proves the surfaces apart.
  const bool convex =
      detail::convex_polytope(a, pose_a0, nullptr) && detail::convex_polytope(b, pose_b0, nullptr);
  int plane_misses = convex ? 0 : kPlaneMisses;
  const std::uint64_t plane_pairs =
      (a.mesh().vertices.size() + b.mesh().vertices.size()) / kPlanePairsPerVertex;
  // One traversal in which every node pair and triangle pair advances on its own: true when it
  // decided (result filled in); else `reached` is the time it proved free.
  ccd::FirstContactLimits limits;
  limits.pairs = kTraversalPairs;
  // The typical triangle size: root radius * sqrt(4 pi / triangles), the side of a triangle of an
  // even tiling of the root sphere.
  const auto triangle_size = [](const Model& m) {
    const Scalar n = static_cast<Scalar>(std::max<std::size_t>(m.mesh().triangles.size(), 1));
    return static_cast<Scalar>(m.root().radius) * std::sqrt(4 * std::numbers::pi / n);
  };
  const Scalar near_gap = kTraversalGap * std::min(triangle_size(a), triangle_size(b));
  const auto traverse = [&](Scalar from, Scalar& reached) {
    const ccd::FirstContact first = ccd::first_contact(
        motion, from, ms, allowance, tolerance::kVolume * scale, mu * tol / 2, limits);
    ++result.iterations;
    reached = first.toi;
    if (first.outcome == ccd::FirstContact::Outcome::miss) {
      result.distance = ms;
      return true;
    }
    if (first.outcome == ccd::FirstContact::Outcome::hit) {
      result.hit = true;
      result.toi = first.toi;
      result.tolerance_decided = !first.proven;
      result.distance = first.distance;
      fill_contact(a, ccd::interpolate_pose(pose_a0, pose_a1, first.toi), b,
                   ccd::interpolate_pose(pose_b0, pose_b1, first.toi), first.triangle_a,
                   first.triangle_b, result.contact);
      return true;
    }
    return false;
  };
  // The closest pair of the last distance query: re-evaluated at the next pose, it seeds the next
  // query with an upper bound of the minimum (most of the hierarchy is then pruned at once).
  bool seeded = false;
  std::uint32_t seed_a = 0;
  std::uint32_t seed_b = 0;
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
    detail::DistanceSeed seed;
    if (seeded) seed = seed_at(a, pa, b, pb, seed_a, seed_b);
    DistanceResult d = detail::seeded_distance(a, pa, b, pb, step, seed);
    ++result.iterations;
    if (std::isfinite(d.distance)) {
      seeded = true;
      seed_a = d.triangle_a;
      seed_b = d.triangle_b;
    }
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
      d = detail::seeded_distance(a, pa, b, pb, settle, detail::make_seed(d));
      ++result.iterations;
      const bool proven = d.intersecting || d.distance + allowance <= ms;
      if (proven || d.distance - ms - allowance <= mu * tol) {
        result.hit = true;
        result.toi = t;
        result.tolerance_decided = !proven;
        result.distance = d.distance;
        fill_contact(a, pa, b, pb, d.triangle_a, d.triangle_b, result.contact);
        break;
      }
      gap = proven_lower_bound(d, settle.abs_tolerance) - ms - allowance;
    }
    // No contact before t + gap / mu (rounded down; the allowance covers the sum's rounding).
    Scalar advance = gap / mu * (1 - 1e-15);
    // Convex pairs: the plane through the closest points, held while both hulls stay on their
    // sides (ccd::plane_step; a second allowance for its vertex projections). It scans every
    // vertex, so a sweep stops trying it after kPlaneMisses steps in a row it did not lengthen.
    if (plane_misses < kPlaneMisses && d.node_pairs >= plane_pairs && d.distance > 0 &&
        std::isfinite(d.distance)) {
      const Vec3 n = (d.point_a - d.point_b) / d.distance;
      const Scalar tau = ccd::plane_step(motion, n, t, ms + 2 * allowance, 1 - t);
      plane_misses = tau > advance ? 0 : plane_misses + 1;
      advance = std::max(advance, tau);
    }
    if (d.node_pairs >= kTraversalNodePairs && gap < near_gap && t + advance < 1 &&
        result.iterations < request.max_iterations) {
      // A query this costly: fine meshes near each other. Every pair advancing on its own costs
      // less than more whole-mesh queries. A traversal that runs out of pairs (a long graze)
      // hands back the time it reached, and the next one gets twice the pairs.
      Scalar reached = t + advance;
      if (traverse(t + advance, reached)) break;
      advance = std::max(advance, reached - t);
      limits.pairs = std::min<std::uint64_t>(2 * limits.pairs, kMaxTraversalPairs);
    }
    if (!(t + advance < 1)) {
      result.distance = d.lower_bound;
      break;
    }
    t += advance;
  }
  return result;
}

}  // namespace antcd
