// Private: the exact intersection test of two closed triangles after the cheap plane rejection,
// shared by triangles_intersect and triangles_within (intersection.cpp).
#pragma once

#include "geometry/predicates.hpp"

namespace antcd::geometry::detail {

// Everything after the cheap plane rejection: `va`/`vb` are the plane values of A's vertices
// against B's plane and of B's vertices against A's plane.
bool intersect_core(const Plane& pa, const Plane& pb, SideValue (&va)[3], SideValue (&vb)[3],
                    Vec3* point);

}  // namespace antcd::geometry::detail
