// Private: the exact intersection test of two closed triangles after the cheap plane rejection,
// shared by triangles_intersect and triangles_within (intersection.cpp).
#pragma once

#include "geometry/predicates.hpp"

namespace antcd::geometry::detail {

// Everything after the cheap plane rejection: `va`/`vb` are the plane values of A's vertices
// against B's plane and of B's vertices against A's plane.
bool intersect_core(const Plane& pa, const Plane& pb, SideValue (&va)[3], SideValue (&vb)[3],
                    Vec3* point);

// Whether the closed segments [a, b] and [c, d], all four points in one plane, meet; tested in the
// projection `pr` (which must not flatten that plane), exact-sign. A common point is written to
// `point` when not null.
bool segments_meet_2d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                      const Projection& pr, Vec3* point);

// Whether the closed segment [p, q] meets the closed triangle (a, b, c) of non-zero area, decided
// with exact-sign predicates (the edge test of the triangle-triangle test).
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c);

}  // namespace antcd::geometry::detail
