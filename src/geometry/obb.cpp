// Separating-axis test between two oriented boxes (15 candidate axes: 3 face normals of each box
// and the 9 cross products of their edge directions).
#include <antcd/geometry.hpp>

#include "geometry/obb_sat.hpp"

namespace antcd::geometry {

bool obb_overlap(const Obb& a, const Obb& b, Scalar margin) {
  const Mat3 r = a.axes.transpose() * b.axes;
  const Vec3 t = a.axes.transpose() * (b.center - a.center);
  return !detail::obb_separated(a.half_extents.array() + margin, b.half_extents, r, t);
}

bool obb_overlap(const Obb& a, const Obb& b, const Transform& b_to_a, Scalar margin) {
  const Mat3 r = a.axes.transpose() * (b_to_a.rotation * b.axes);
  const Vec3 t = a.axes.transpose() * (b_to_a.apply(b.center) - a.center);
  return !detail::obb_separated(a.half_extents.array() + margin, b.half_extents, r, t);
}

}  // namespace antcd::geometry
