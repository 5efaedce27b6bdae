// Private: the contact normal and depth of a triangle pair whose intersection is already known
// (penetration.cpp), so collide() does not repeat the exact test.
#pragma once

#include <antcd/geometry.hpp>

namespace antcd::geometry::detail {

// Intersecting (or touching) triangles: the separating-axis penetration of triangle_penetration.
TrianglePenetration intersecting_penetration(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                             const Vec3& b0, const Vec3& b1, const Vec3& b2);

// Triangles apart with closest points pa (on A) and pb (on B).
TrianglePenetration apart_penetration(const Vec3& pa, const Vec3& pb);

}  // namespace antcd::geometry::detail
