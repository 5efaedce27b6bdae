// Private: the 15-axis separating-axis test between two oriented boxes, inline so that the
// hierarchy's traversal (src/bvh/traverse.hpp) and geometry::obb_overlap share one definition;
// and the 13-axis test between a triangle and a box the traversal uses to drop a large leaf's
// triangles one by one.
#pragma once

#include <antcd/math.hpp>

#include <algorithm>
#include <cmath>

namespace antcd::geometry::detail {

// Box b is given by its axes (columns) and centre expressed in a's box coordinates:
// r = a.axes^T * b.axes, t = a.axes^T * (b.center - a.center). abs_r is |r| plus a small epsilon:
// when two edges are nearly parallel their cross product is nearly zero and rounding could
// otherwise report a separating axis that is not one.
inline constexpr Scalar kAbsRotationEps = 1e-12;
inline Mat3 obb_abs_rotation(const Mat3& r) { return r.cwiseAbs().array() + kAbsRotationEps; }

/// The six face axes of the 15-axis test below (a's three, then b's three): true when one of them
/// separates the boxes. Missing the nine edge-edge axes, it reports fewer separations, never one
/// that the full test would not; a filter in front of exact tests may use it alone.
inline bool obb_face_separated(const Vec3& ea, const Vec3& eb, const Mat3& r, const Mat3& abs_r,
                               const Vec3& t) {
  // Axes of a.
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > ea[i] + abs_r.row(i).dot(eb)) return true;
  }
  // Axes of b.
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(r.col(j))) > abs_r.col(j).dot(ea) + eb[j]) return true;
  }
  return false;
}

inline bool obb_separated(const Vec3& ea, const Vec3& eb, const Mat3& r, const Vec3& t) {
  const Mat3 abs_r = obb_abs_rotation(r);
  if (obb_face_separated(ea, eb, r, abs_r, t)) return true;
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

/// True when a separating axis exists between the triangle (u0, u1, u2) and the box centred at
/// the origin with the coordinate axes and half extents `e` (the triangle given in the box's
/// coordinates). Axes: the box's three, the triangle's normal, and the nine products of a box
/// axis with a triangle edge (Akenine-Möller's triangle/box overlap test). Every vertex is
/// projected on every axis (nothing is assumed about vertices that should project alike), so
/// rounding only moves projections by about 1e-16 of |axis| times the coordinates' magnitude: a
/// caller that widens `e` by more than that (the traversal's margin, 1e-9 of the scene's scale)
/// never sees a false separation, whatever the axis' length.
inline bool triangle_box_separated(const Vec3& u0, const Vec3& u1, const Vec3& u2, const Vec3& e) {
  // Axes of the box.
  for (int k = 0; k < 3; ++k) {
    if (std::min({u0[k], u1[k], u2[k]}) > e[k] || std::max({u0[k], u1[k], u2[k]}) < -e[k]) {
      return true;
    }
  }
  const auto separated_along = [&](const Vec3& axis) {
    const Scalar p0 = axis.dot(u0);
    const Scalar p1 = axis.dot(u1);
    const Scalar p2 = axis.dot(u2);
    const Scalar r = e.dot(axis.cwiseAbs());
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
  };
  const Vec3 f0 = u1 - u0;
  const Vec3 f1 = u2 - u1;
  const Vec3 f2 = u0 - u2;
  // The triangle's normal.
  if (separated_along(f0.cross(f1))) return true;
  // Box axis x triangle edge: e_x x f = (0, -f.z, f.y), e_y x f = (f.z, 0, -f.x),
  // e_z x f = (-f.y, f.x, 0).
  for (const Vec3* f : {&f0, &f1, &f2}) {
    if (separated_along(Vec3(0, -f->z(), f->y())) || separated_along(Vec3(f->z(), 0, -f->x())) ||
        separated_along(Vec3(-f->y(), f->x(), 0))) {
      return true;
    }
  }
  return false;
}

}  // namespace antcd::geometry::detail
