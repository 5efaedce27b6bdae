// antcd/ccd.hpp — continuous collision detection (CCD): primitives moving linearly and meshes
// moving rigidly between two poses.
//
// Definitions
// - Time runs over [0, 1]. A primitive's corners move LINEARLY: x(t) = (1 - t) x0 + t x1.
// - A rigid motion between two poses P0 = (R0, T0) and P1 = (R1, T1): the translation is
//   interpolated linearly, T(t) = (1 - t) T0 + t T1, and the rotation turns at constant angular
//   velocity about the model's origin along the shorter arc (quaternion slerp from R0 to R1; a
//   half turn, where both arcs are equally short, takes the arc Eigen's slerp takes). A model
//   point p is at R(t) p + T(t) in the world. interpolate_pose() returns that pose.
// - Time of impact t*: the first t in [0, 1] at which the two moving sets come within distance
//   `min_separation` (>= 0; 0: they touch). Sets are closed: touching at a vertex or an edge, and
//   contact exactly at t = 0 or t = 1, count.
//
// Guarantees (certified, never estimated)
// - Conservative: when the motions make contact, the result is a hit and toi <= t*. No contact is
//   ever missed; floating-point rounding is bounded a priori and covered (see ccd.cpp / sweep.cpp).
// - A hit is either proven (tolerance_decided == false: at toi the sets are within min_separation,
//   up to the rounding of the proof's arithmetic) or decided by the tolerance (tolerance_decided ==
//   true): the search could not separate the sets in a time window of width <= time_tolerance
//   starting at toi, and they come within the tolerance's reach there (per primitive and mesh
//   query below). A tolerance-decided hit may be a false positive; if t* exists it is >= toi.
//
// Primitives (vertex_face, edge_edge): inclusion-based root finding in the style of Tight
// Inclusion (Wang et al. 2021). The function F(t, u, v) = difference of the two moving points is
// multilinear, so the box of its 8 corner values bounds it over a parameter box; the box is widened
// by an a-priori bound of the rounding of those evaluations, and by min_separation on each axis.
// Parameter boxes are bisected (t while wider than time_tolerance, u and v while they can move F
// by more than W = time_tolerance * 2D, D being the largest displacement |x1 - x0| (infinity
// norm) of a corner) until the inclusion excludes the origin, or each axis of the inclusion is
// settled (at most W wide, or wholly within min_separation) with the window at most
// time_tolerance long, or every parameter is at its tolerance. Only windows before the earliest
// accepted box are searched further; the result is the earliest accepted box's start. On a
// tolerance-decided hit, at a time in [toi, toi + time_tolerance] a point of each primitive
// lie within min_separation + 3W + rounding of each other on EACH axis (so within sqrt(3) times
// that in Euclidean distance). When the
// search needs more than max_boxes boxes (very degenerate input), it stops with a hit at the
// earliest time not yet excluded (tolerance_decided, budget_exhausted).
// With min_separation == 0 a filter runs first: a contact needs the four points coplanar, so time
// pieces where the coplanarity cubic (Bernstein form, each coefficient with a certified rounding
// bound) keeps one strict sign are skipped, and the earliest remaining windows are checked at a
// parameter guess (accepted only within 2W per axis) before the window search below runs on them
// alone (and on the rest of [0, 1] where the cubic may vanish all along: motion in one plane).
// It removes no window that can hold a contact (docs/ccd.md, "Primitives").
// The window search (alone when min_separation > 0), earliest first: a window is excluded when
// one direction certifies the primitives farther apart than min_separation over all of it (a
// support-function bound, concave in t, checked at both ends with its rounding), ends the search
// at its start when a contact is proven there, or, once at most time_tolerance long, when the
// primitives are within min_separation + 2W (Euclidean) there; otherwise it is halved, and a
// window of the tolerance that is none of these gets the inclusion search above.
//
// Thread safety: every function here is a pure const computation; call it from any thread.
// Errors: non-finite coordinates, min_separation < 0 or not finite, time_tolerance <= 0 or not
// finite: antcd::ArgumentError naming the argument.
#pragma once

#include <antcd/collide.hpp>
#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include <array>
#include <cstdint>

namespace antcd::ccd {

struct PrimitiveResult {
  bool hit = false;
  /// Time of impact in [0, 1] when hit (1 otherwise).
  Scalar toi = 1;
  /// The hit came from the tolerance, not from a proof (see the header comment).
  bool tolerance_decided = false;
  /// The box budget ran out; the hit is a conservative stop (tolerance_decided is true then).
  bool budget_exhausted = false;
  /// Parameter boxes examined.
  std::uint32_t boxes = 0;
};

/// Largest number of parameter boxes one primitive query examines before stopping conservatively.
inline constexpr std::uint32_t kMaxBoxes = 1u << 20;

/// Vertex–face CCD. `at_t0` = {vertex, face corner 0, 1, 2} at t = 0, `at_t1` the same at t = 1.
/// The face is the closed triangle (a zero-area face is its segments / point).
ANTCD_API PrimitiveResult vertex_face(const std::array<Vec3, 4>& at_t0,
                                      const std::array<Vec3, 4>& at_t1, Scalar min_separation = 0,
                                      Scalar time_tolerance = 1e-6);

/// Edge–edge CCD. `at_t0` = {edge a end 0, a end 1, edge b end 0, b end 1} at t = 0, `at_t1` the
/// same at t = 1. Edges are closed segments.
ANTCD_API PrimitiveResult edge_edge(const std::array<Vec3, 4>& at_t0,
                                    const std::array<Vec3, 4>& at_t1, Scalar min_separation = 0,
                                    Scalar time_tolerance = 1e-6);

/// The pose at time t in [0, 1] of the rigid motion from p0 to p1 (see the definitions above).
ANTCD_API Transform interpolate_pose(const Transform& p0, const Transform& p1, Scalar t);

}  // namespace antcd::ccd
