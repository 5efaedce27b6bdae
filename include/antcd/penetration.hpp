// antcd/penetration.hpp — penetration depth of two closed models (solids), with certified bounds.
//
// Definitions
// - Solids: a closed model (Model::is_closed) bounds the solid of its surface (points.hpp: non-zero
//   winding number). Both models must be closed; an open model is an ArgumentError naming it.
// - Frames: each Model's geometry is in its own frame, pose_a / pose_b map it to the world. Every
//   vector and point of the result is in the WORLD frame.
// - Penetration depth PD(A, B): the length of the shortest translation t (world frame) of A after
//   which the interiors of A + t and B no longer overlap; 0 when they do not overlap. The
//   direction is n = t / |t|: the way to move A (move B by -t instead for the same effect).
// - This is the depth of the SOLIDS. Contact::depth (collide.hpp) is something else: the depth of
//   one triangle pair (FCL's mesh semantics), not the solids' depth.
//
// What is returned and what is guaranteed
// - Convex pairs (both models convex, see Convexity): exact = true, lower == upper == PD up to
// rounding (a few ulps of the coordinates),
//   found by the separating-axis theorem over the facets of the Minkowski difference A - B (face
//   normals of A and B, and the edge pairs whose Gauss-map arcs cross). point_a on A's surface and
//   point_b on B's surface with point_a + upper * direction == point_b (A moved by the depth
//   touches B there).
// - General closed solids: exact = false and [lower, upper] is a certified interval that always
//   contains the true PD, even when not converged:
//   * lower: for a point p strictly inside both solids, the balls of radius dist(p, ∂A) and
//     dist(p, ∂B) about p lie in A and in B, so any translation separating the interiors is at
//     least dist(p, ∂A) + dist(p, ∂B) long. lower is that sum at the best p found (witness), each
//     distance reduced by a rounding allowance of 1e-10 of the coordinates' scale (far above the
//     rounding of the point queries), and 0 when no point inside both was found.
//   * upper: |t| of a translation t (rounded up) for which collide() with volume = true, delta 0,
//     at exactly the pose of A translated by t, reported the models apart (surfaces disjoint and
//     neither inside the other): the interiors are then disjoint.
//   The search refines both until upper - lower <= max(abs_tolerance, rel_tolerance * upper)
//   (converged = true) or the budget (max_evaluations collide calls, max_seconds) runs out
//   (converged = false; the interval is still certified; upper is +inf when no separating
//   translation was found within the budget). Moving A by upper * direction always separates the
//   solids; point_a / point_b are the points of A's and B's surfaces nearest to the witness.
// - overlapping: true when the interiors certainly overlap (a point inside both was found, or the
//   convex separating-axis test found no separating axis). False: the interiors are disjoint
//   (collide found the models apart, or the convex test found a separating or touching axis), or,
//   for general solids whose surfaces meet, no interior point was found: they touch or overlap by
//   at most `upper` (PD is then in [0, upper]).
// - witness: a world point inside both solids (winding numbers, points.hpp) when overlapping
//   (convex pairs: inside both by the face planes, by more than 1e-9 of the coordinates' scale).
//
// Convexity (PenetrationRequest::shape = Auto): a closed mesh is convex when it is one connected
// piece and no edge is reflex: the far vertex of each neighbouring triangle lies behind the other
// triangle's plane or within 1e-10 of the model's size of it (coplanar neighbours then form one
// face). A locally convex closed surface that covers itself twice would pass; declare
// Shape::General for such input.
//
// Cost: convex pairs: the polytope of each Model is derived once (O(n log n), kept with the
// Model), then per query O(F) supports by hill climbing and the edge pairs that survive an
// inner-ball bound and a Gauss-map grid (at worst E_A * E_B; bench/penetration_bench.cpp). General
// pairs: a few exact collide() calls (2 on the benchmark's pairs; at most max_evaluations), a
// distance query, and point queries for the witness (their per-model cache is built on first use,
// see points.hpp).
//
// Thread safety: penetration() only reads its Models; any number of threads may query the same
// Models concurrently.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/export.hpp>

#include <cstdint>

namespace antcd {

struct PenetrationRequest {
  /// How to treat the models: detect convexity (Auto: the exact path for convex pairs of up to
  /// about 6000 x 6000 edges, the general bounds otherwise), require it (Convex: the exact path at
  /// any size; ArgumentError naming a model that is not convex), or use the general bounds
  /// (General).
  enum class Shape { Auto, Convex, General };
  Shape shape = Shape::Auto;
  /// Stop refining once upper - lower <= max(abs_tolerance, rel_tolerance * upper).
  /// abs_tolerance >= 0 (mesh units), 0 <= rel_tolerance < 1; not both 0.
  Scalar abs_tolerance = 0;
  Scalar rel_tolerance = 0.01;
  /// Budget of the general search: exact collide() calls (>= 1), and wall seconds (0: no limit).
  std::uint32_t max_evaluations = 64;
  double max_seconds = 0;
};

struct PenetrationResult {
  /// The interiors overlap (see the header comment).
  bool overlapping = false;
  /// Convex path: lower == upper is the depth up to rounding.
  bool exact = false;
  /// upper - lower is within the requested tolerance.
  bool converged = false;
  /// Certified bounds of the penetration depth: lower <= PD <= upper (mesh units).
  Scalar lower = 0;
  Scalar upper = 0;
  /// Unit, world frame: the way to move A (A + upper * direction is apart from B).
  Vec3 direction = Vec3::UnitX();
  /// World point inside both solids (meaningful when overlapping).
  Vec3 witness = Vec3::Zero();
  /// World points on A's and on B's surface (convex: the touching points after the move).
  Vec3 point_a = Vec3::Zero();
  Vec3 point_b = Vec3::Zero();
  /// Exact collide() calls made (general path).
  std::uint32_t evaluations = 0;
};

/// Penetration depth of the solids bounded by two closed posed models. Throws ArgumentError when a
/// model is not closed (naming it) or a request field is out of range.
ANTCD_API PenetrationResult penetration(const Model& a, const Transform& pose_a, const Model& b,
                                        const Transform& pose_b,
                                        const PenetrationRequest& request = {});

/// Signed distance of two closed posed models: the distance between the surfaces (distance()) when
/// the solids are apart, 0 when they touch without interior overlap, and -PD when their interiors
/// overlap, PD the penetration depth above (FCL's convention for its convex shapes): the exact
/// value for convex pairs, else the certified upper bound of PD once converged (so -PD >= the
/// true signed distance; lower_bound is then -upper too, and approximate says whether it was
/// exact). Nested solids (surfaces apart, one inside the other) overlap; point_a / point_b are then
/// penetration()'s points. The depth is refined to max(request.abs_tolerance,
/// request.rel_tolerance * depth), or to 1 % when both are 0. Throws ArgumentError naming a model
/// that is not closed, or a request field out of range (as distance()). Const and thread-safe.
ANTCD_API DistanceResult signed_distance(const Model& a, const Transform& pose_a, const Model& b,
                                         const Transform& pose_b,
                                         const DistanceRequest& request = {});

/// Whether a closed model is convex (the test of the header comment, exact predicates). False for
/// an open model.
ANTCD_API bool is_convex(const Model& model);

}  // namespace antcd
