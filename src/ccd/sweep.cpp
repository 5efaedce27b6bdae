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

#include "ccd/motion.hpp"
#include "ccd/swept_proximity.hpp"
#include "distance/seeded.hpp"
#include "util/check.hpp"
#include "util/pose_check.hpp"

namespace antcd {
namespace {

/// The loop's distance queries may stop within this fraction of the distance (the lower bound is
/// still proven); only the stopping decision needs the exact distance. With the queries seeded by
/// the last closest pair (see seed_at), proving more of the distance pays: callgrind on the
/// 12-frame production line of seed 3, 0.5 / 0.3 / 0.15 / 0.05 / 0 (exact): 7.19 / 6.49 / 6.19
/// / 6.26 / 9.55 G instructions (unseeded, 0.5: 8.45 G).
constexpr Scalar kStepRelTolerance = 0.15;
/// Local advancement (see advance_locally) runs when its window reaches at least this many
/// whole-mesh steps ahead (the endgame of an approach) ...
constexpr Scalar kWindowSteps = 2;
/// ... with a reach of at most this fraction of the typical triangle size, root radius *
/// sqrt(4 pi / triangles) (the side of a triangle of an even tiling of the root sphere), so that
/// only a few triangle pairs are within reach.
constexpr Scalar kWindowReach = 0.25;
/// ... and at most this many whole-mesh steps long (a longer window holds more pairs). With the
/// per-pair rates (pair_rate), 12-frame production line of seed 3 (callgrind; 1024 pairs at most):
/// spans 8 / 16 / 32: 5.36 / 5.22 / 5.19 G instructions; 4: 6.45 G (256 pairs).
constexpr Scalar kWindowSpan = 16;
/// ... and only after a hierarchy query that examined at least this many node pairs (below, the
/// whole-mesh steps are cheaper than collecting a window's pairs: thin sheets, 50-300 node pairs,
/// 6-30 us a query, against 100-300 us a window).
constexpr std::uint64_t kWindowNodePairs = 400;
/// Above this many triangle pairs within reach of a window, the local advancement is skipped.
/// Same scene (span 8): 256 / 512 / 1024 / 2048 / 4096 pairs: 5.65 / 5.53 / 5.36 / 5.63 / 6.23 G.
constexpr std::size_t kMaxWindowPairs = 1024;
/// Depth of the earliest-first bisection that proves stretches of the motion apart before the
/// advancement starts (pieces down to 2^-depth of the motion).
/// Scene production line (`antcd scene generate --frames 60 --seed 3`): depth 3 / 4 / 6 settle
/// 5893 / 5919 / 5956 of 8473 sweeps this way; 4 was the fastest of one run each.
constexpr int kBisectDepth = 4;
/// Node pairs one interval test may examine before giving up: a piece that is apart but close
/// costs a whole proximity traversal (7 000-15 000 node pairs seen without a cap, more than the
/// advancement it saves). 300 settled 5888 sweeps, 1000 settled 5919 and was faster.
constexpr std::uint32_t kApartBudget = 1000;
/// Advancement steps on one window's pairs before handing back to the whole-mesh loop.
constexpr int kMaxWindowSteps = 1000;

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

void fill_contact(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                  const DistanceResult& d, Contact& c) {
  c.triangle_a = d.triangle_a;
  c.triangle_b = d.triangle_b;
  c.point = (d.point_a + d.point_b) / 2;
  c.distance = d.distance;
  const auto x = posed_triangle(a, pa, d.triangle_a);
  const auto y = posed_triangle(b, pb, d.triangle_b);
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

/// Scratch storage of the local advancement, reused across one sweep's windows.
struct LocalPairs {
  CollisionResult near;      // the triangle pairs within reach; Contact::distance is refreshed
  std::vector<Scalar> at;    // the time of each pair's distance
  std::vector<Scalar> rate;  // how fast each pair's distance may fall from then on
};

/// How fast the distance `d` of triangle ta of A and tb of B (closest points d.pa, d.pb at the
/// poses of time s) may fall after s, at most mu. With the rotations held at their poses at s,
/// the pair only translates, by the relative velocity v of A against B: the distance between two
/// convex sets whose offset moves along a line is a convex function of time, so it stays above its
/// tangent at s, whose slope is n . v (n the unit vector from B's closest point to A's). Each
/// point p of A strays from its held-rotation path by at most theta_a |p| per unit time (the
/// chord of its arc about the model origin), and likewise for B, so the distance falls by at most
/// theta_a rho_a + theta_b rho_b - n . v per unit time (rho the largest vertex norm of the
/// triangle in its model's frame; may be negative: the bound then rises). n's direction is
/// allowed an error of 2 allowance / |pa - pb|; pairs nearer than 4 allowance use mu.
Scalar pair_rate(const ccd::RigidPair& m, const Vec3& v, Scalar mu, Scalar allowance,
                 const geometry::TriangleDistance& d, std::uint32_t ta, std::uint32_t tb) {
  if (!(d.distance > 4 * allowance)) return mu;
  const auto largest_norm = [](const Model& model, std::uint32_t i) {
    const auto& t = model.mesh().triangles[i];
    const auto& p = model.mesh().vertices;
    return std::max({p[t[0]].norm(), p[t[1]].norm(), p[t[2]].norm()});
  };
  const Scalar turning =
      tolerance::widened(m.theta_a * largest_norm(m.a, ta) + m.theta_b * largest_norm(m.b, tb));
  const Vec3 n = (d.pa - d.pb) / d.distance;
  const Scalar closing =
      -n.dot(v) + v.norm() * (2 * allowance / d.distance + tolerance::kArithmetic);
  return std::min(mu, turning + closing);
}

/// Conservative advancement over the window [t, t + h] on the few triangle pairs that can touch in
/// it: no point moves faster than mu, so a pair more than ms + mu h apart at t stays more than ms
/// apart until t + h, and collide() with that delta (plus twice the allowance for its rounding)
/// lists every other pair. A pair's distance d at time s' bounds it from below at s by
/// d - rate (s - s'), rate = mu for the pairs as listed and pair_rate's bound once recomputed; each
/// step recomputes the pairs whose bound may reach min_separation first (within twice the
/// earliest such time) until that earliest pair's distance is from s, and advances to its time.
/// Returns the time reached (nothing touches before it): t + h when the window is clear, else the
/// first time a pair's exact distance is within ms + allowance + mu * tol (the whole-mesh loop
/// decides there); -1 when more than kMaxWindowPairs pairs are within reach (nothing done).
Scalar advance_locally(const ccd::RigidPair& m, Scalar t, Scalar h, Scalar mu, Scalar ms,
                       Scalar allowance, Scalar tol, LocalPairs& local) {
  CollisionRequest reach;
  reach.delta = ms + mu * h + 2 * allowance;
  reach.all_contacts = true;
  reach.max_contacts = kMaxWindowPairs + 1;
  auto& pairs = local.near.contacts;
  collide(m.a, ccd::interpolate_pose(m.a0, m.a1, t), m.b, ccd::interpolate_pose(m.b0, m.b1, t),
          reach, local.near);
  if (pairs.size() > kMaxWindowPairs) return -1;
  const Scalar end = t + h;
  if (pairs.empty()) return end;
  local.at.assign(pairs.size(), t);
  local.rate.assign(pairs.size(), mu);
  const Vec3 v = (m.a1.translation - m.a0.translation) - (m.b1.translation - m.b0.translation);
  constexpr Scalar kNever = std::numeric_limits<Scalar>::infinity();
  // The earliest time pair i's bound may reach ms + allowance (+inf: it never falls).
  const auto reach_time = [&](std::size_t i) {
    const Scalar gap = pairs[i].distance - ms - allowance;
    return local.rate[i] > 0 ? local.at[i] + gap / local.rate[i] : kNever;
  };
  Scalar s = t;
  for (int step = 0; step < kMaxWindowSteps; ++step) {
    const Transform pa = ccd::interpolate_pose(m.a0, m.a1, s);
    const Transform pb = ccd::interpolate_pose(m.b0, m.b1, s);
    // Recompute the pairs whose bound may reach the separation within twice the earliest such
    // time from s (plus the tolerance) until the earliest one is a distance at s.
    std::size_t nearest = 0;
    while (true) {
      Scalar first = kNever;
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const Scalar r = reach_time(i);
        if (r < first) {
          first = r;
          nearest = i;
        }
      }
      if (first == kNever) return end;  // no bound falls: the window is clear
      if (local.at[nearest] == s) break;
      const Scalar limit = s + 2 * std::max<Scalar>(first - s, 0) + tol;
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (local.at[i] == s || reach_time(i) > limit) continue;
        const auto x = posed_triangle(m.a, pa, pairs[i].triangle_a);
        const auto y = posed_triangle(m.b, pb, pairs[i].triangle_b);
        const geometry::TriangleDistance d =
            geometry::triangle_distance(x[0], x[1], x[2], y[0], y[1], y[2]);
        pairs[i].distance = d.distance;
        local.at[i] = s;
        local.rate[i] = pair_rate(m, v, mu, allowance, d, pairs[i].triangle_a, pairs[i].triangle_b);
      }
    }
    // The earliest pair's bound is its distance at s: stop on it or advance to its time.
    const Scalar gap = pairs[nearest].distance - ms - allowance;
    if (gap <= mu * tol) return s;
    const Scalar next = s + gap / local.rate[nearest] * (1 - 1e-15);
    if (!(next < end)) return end;
    s = next;
  }
  return s;
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
  const ccd::RigidPair motion{a,
                              pose_a0,
                              pose_a1,
                              b,
                              pose_b0,
                              pose_b1,
                              tolerance::widened(relative_move.norm()),
                              ccd::rotation_angle(pose_a0.rotation, pose_a1.rotation),
                              ccd::rotation_angle(pose_b0.rotation, pose_b1.rotation)};
  const Scalar mu = tolerance::widened(motion.speed + motion.theta_a * ra + motion.theta_b * rb);
  const Scalar scale = ra + rb + ms + pose_a0.translation.norm() + pose_a1.translation.norm() +
                       pose_b0.translation.norm() + pose_b1.translation.norm();
  // The poses, the distance and the time steps are each within a few 1e-16 of the scene's size
  // (see sweep.hpp).
  const Scalar allowance = tolerance::kArithmetic * scale;

  LocalPairs local;
  // No local advancement until the gap is a quarter of one where too many pairs were in reach.
  Scalar local_below = std::numeric_limits<Scalar>::infinity();
  const auto triangle_size = [](const Model& m) {
    const Scalar n = static_cast<Scalar>(std::max<std::size_t>(m.mesh().triangles.size(), 1));
    return static_cast<Scalar>(m.root().radius) * std::sqrt(4 * std::numbers::pi / n);
  };
  const Scalar window_reach = kWindowReach * std::min(triangle_size(a), triangle_size(b));

  SweepResult result;
  result.motion_bound = mu;
  // Whole stretches of the motion proven apart at once (most swept pairs of a scene never touch).
  Scalar slack = std::numeric_limits<Scalar>::infinity();
  Scalar t = apart_until(motion, 0, ms + allowance, kBisectDepth, result.iterations, slack);
  if (t >= 1) {
    result.distance = ms + slack;
    return result;
  }
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
        fill_contact(a, pa, b, pb, d, result.contact);
        break;
      }
      gap = proven_lower_bound(d, settle.abs_tolerance) - ms - allowance;
    }
    // No contact before t + gap / mu (rounded down; the allowance covers the sum's rounding).
    Scalar advance = gap / mu * (1 - 1e-15);
    const Scalar window =
        std::min({1 - t, (window_reach - ms - 2 * allowance) / mu, kWindowSpan * advance});
    if (window >= kWindowSteps * advance && gap < local_below && d.node_pairs >= kWindowNodePairs) {
      const Scalar reached = advance_locally(motion, t, window, mu, ms, allowance, tol, local);
      ++result.iterations;
      if (reached < 0) {
        local_below = gap / 4;
      } else {
        advance = std::max(advance, reached - t);
      }
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
