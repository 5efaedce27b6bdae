// antcd/geometry.hpp — bounding volumes and triangle predicates (pure functions, no state).
//
// Conventions
// - Triangles are closed sets: their boundary (edges and vertices) belongs to them. Two triangles
//   that share only a vertex, or touch edge-on-edge, or overlap while coplanar, INTERSECT.
// - Distances are Euclidean, in mesh units, and never negative; penetration depth is a separate
//   query (triangle_penetration).
// - All inputs are in one common frame chosen by the caller.
// - Degenerate (zero-area) triangles are not supported by the predicates; the hierarchy filters
//   them out before any query (see Model).
// - Every function here is reentrant: no globals, no allocation.
#pragma once

#include <antcd/export.hpp>
#include <antcd/math.hpp>

namespace antcd {

/// Bounding sphere.
struct Sphere {
  Vec3 center = Vec3::Zero();
  Scalar radius = 0;
};

/// Oriented bounding box. `axes` holds the three unit box axes as columns (a right-handed
/// orthonormal basis); `half_extents` the half side lengths along them. A point p is inside when
/// |axes.col(k).dot(p - center)| <= half_extents[k] for k = 0, 1, 2.
struct Obb {
  Vec3 center = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  Vec3 half_extents = Vec3::Zero();

  [[nodiscard]] Scalar volume() const { return 8 * half_extents.prod(); }
};

/// How the OBB axes of a hierarchy node are fitted (paper, Eqs. 1–3).
enum class CovarianceMethod {
  /// Eqs. 1–2: mean of the triangles' vertices, covariance of the vertices about it.
  VertexMean,
  /// Eq. 3 into Eq. 2: the mean is the area-weighted combined centroid of the triangles, and each
  /// triangle contributes its vertices' scatter about it weighted by its area (the paper's
  /// improvement; insensitive to non-uniform tessellation). Default.
  AreaWeightedCentroid,
};

namespace geometry {

/// True for a zero-area triangle, or numerically so: twice its area (|(b-a)×(c-a)|) is at most
/// 1e-12 times its longest edge squared (needle and cap shaped slivers with all three vertices on
/// one line up to rounding). Such triangles are left out of hierarchies and queries.
ANTCD_API bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c);

/// Orientation of d against the plane through a, b, c: the determinant
/// | a-d ; b-d ; c-d |. Positive when d lies below the plane (a, b, c counter-clockwise when seen
/// from above), zero when coplanar.
ANTCD_API Scalar orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Whether the closed triangles (a0, a1, a2) and (b0, b1, b2) share at least one point
/// (touching counts). When they do and `point` is not null, one common point is written to it.
ANTCD_API bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                   const Vec3& b1, const Vec3& b2, Vec3* point = nullptr);

/// Signed solid angle (steradians, in [-2π, 2π]) of triangle (a, b, c) seen from p: positive when
/// (a, b, c) is counter-clockwise seen from p. Summed over a closed, consistently oriented surface
/// it is ±4π for a point inside and 0 outside (the winding number times 4π).
ANTCD_API Scalar solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Squared distance from p to the closed triangle (a, b, c); the closest point is written to
/// `closest` when not null.
ANTCD_API Scalar point_triangle_distance_squared(const Vec3& p, const Vec3& a, const Vec3& b,
                                                 const Vec3& c, Vec3* closest = nullptr);

/// Squared distance between the closed segments [p0, p1] and [q0, q1]; the closest points on
/// each are written to `cp` and `cq` when not null. Handles degenerate (point) segments.
ANTCD_API Scalar segment_segment_distance_squared(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                                  const Vec3& q1, Vec3* cp = nullptr,
                                                  Vec3* cq = nullptr);

/// Distance between two closed triangles (0 when they intersect) with a closest pair of points
/// (`pa` on the first, `pb` on the second; equal to a common point when they intersect).
struct TriangleDistance {
  Scalar distance = 0;
  Vec3 pa = Vec3::Zero();
  Vec3 pb = Vec3::Zero();
};
ANTCD_API TriangleDistance triangle_distance(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                             const Vec3& b0, const Vec3& b1, const Vec3& b2);

/// Contact normal and signed depth of two closed triangles (see triangle_penetration).
struct TrianglePenetration {
  Vec3 normal = Vec3::UnitZ();  ///< unit, points from the second triangle (B) towards the first (A)
  Scalar depth = 0;             ///< >= 0 when they intersect, -distance when apart
};

/// The one definition of a contact's normal n and depth d used throughout antcd.
/// - Intersecting (or touching) triangles: d >= 0 is the length of the shortest translation that
///   separates them, found by the separating-axis theorem over the candidate axes of two
///   triangles: A's face normal, B's face normal and the 9 cross products of an edge of A with an
///   edge of B (the face normals of the Minkowski difference A - B, so the minimum over them is
///   the exact penetration depth). Moving A by d along n, or B by d along -n, leaves them touching;
///   any more separates them; every translation shorter than d leaves them intersecting. Touching
///   triangles have d = 0 with the axis along which they touch. Ties go to the first axis in the
///   order above, and of its two directions to the one with n·(nB - nA) >= 0 (for coplanar faces of
///   two solids resting on each other, n = B's outward normal). Edge pairs within about 1e-6 rad of
///   parallel are skipped (their cross product has no reliable direction).
/// - Triangles apart (distance dist > 0): n = (pa - pb) / dist from B's closest point to A's, and
///   d = -dist.
/// Computed in doubles (not exact): about 1e-15 x the triangles' size for well-shaped triangles.
/// Whether the triangles intersect is the exact predicate triangles_intersect.
ANTCD_API TrianglePenetration triangle_penetration(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                                   const Vec3& b0, const Vec3& b1, const Vec3& b2);

/// The query used by collision detection with threshold delta >= 0: true when the triangles
/// intersect or their distance is <= delta. With delta == 0 this is exactly triangles_intersect.
/// On true, `point` (when not null) receives a contact point: a common point when they intersect,
/// else the midpoint of the closest points; `distance` (when not null) receives the distance.
ANTCD_API bool triangles_within(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                const Vec3& b1, const Vec3& b2, Scalar delta, Vec3* point = nullptr,
                                Scalar* distance = nullptr);

/// Separating-axis test (15 axes) between box `a` and box `b`, both in the same frame, with `a`'s
/// half extents grown by `margin` >= 0 (a box that contains a's Minkowski sum with a ball of radius
/// margin, so the test stays conservative for distance queries). True when no separating axis was
/// found (overlap or touching).
ANTCD_API bool obb_overlap(const Obb& a, const Obb& b, Scalar margin = 0);

/// Same test with b given in its own frame and the rigid motion `b_to_a` mapping it into a's frame.
ANTCD_API bool obb_overlap(const Obb& a, const Obb& b, const Transform& b_to_a, Scalar margin);

/// Sphere test: true when the spheres are within `margin` of each other (touching counts).
inline bool sphere_overlap(const Sphere& a, const Sphere& b, Scalar margin = 0) {
  const Scalar r = a.radius + b.radius + margin;
  return (a.center - b.center).squaredNorm() <= r * r;
}

}  // namespace geometry
}  // namespace antcd
