// Private: the 15-axis separating-axis test between two oriented boxes, inline so that the
// hierarchy's traversal (src/bvh/traverse.hpp) and geometry::obb_overlap share one definition.
#pragma once

#include <antcd/math.hpp>

#include <cmath>

namespace antcd::geometry::detail {

// Box b is given by its axes (columns) and centre expressed in a's box coordinates:
// r = a.axes^T * b.axes, t = a.axes^T * (b.center - a.center).
inline bool obb_separated(const Vec3& ea, const Vec3& eb, const Mat3& r, const Vec3& t) {
  // |r| plus a small epsilon: when two edges are nearly parallel their cross product is nearly
  // zero and rounding could otherwise report a separating axis that is not one.
  constexpr Scalar kEps = 1e-12;
  Mat3 abs_r = r.cwiseAbs().array() + kEps;

  // Axes of a.
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > ea[i] + abs_r.row(i).dot(eb)) return true;
  }
  // Axes of b.
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(r.col(j))) > abs_r.col(j).dot(ea) + eb[j]) return true;
  }
  // Cross products a_i x b_j.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const Scalar ra = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const Scalar rb = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      const Scalar dist = std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j));
      if (dist > ra + rb) return true;
    }
  }
  return false;
}

}  // namespace antcd::geometry::detail
