// Private: bounds on a rigid motion (antcd/ccd.hpp's interpolation) shared by the mesh sweep and
// the World's continuous queries.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>
#include <antcd/tolerances.hpp>

namespace antcd::ccd {

/// Angle of the rotation from r0 to r1 along the shorter arc (the slerp's total angle), rounded up.
inline Scalar rotation_angle(const Mat3& r0, const Mat3& r1) {
  const Scalar angle = Quat(r0).angularDistance(Quat(r1));
  return tolerance::widened(angle) + 1e-15;
}

/// Radius about the model origin holding every vertex of the model's tree (root sphere).
inline Scalar origin_radius(const Model& m) {
  return m.root().center.norm() + static_cast<Scalar>(m.root().radius);
}

}  // namespace antcd::ccd
