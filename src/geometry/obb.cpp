// Separating-axis test between two oriented boxes (15 candidate axes: 3 face normals of each box
// and the 9 cross products of their edge directions).
#include <antcd/geometry.hpp>

#include <cmath>

namespace antcd::geometry {

namespace {

// Box b is given by its axes (columns) and centre expressed in a's box coordinates:
// r = a.axes^T * b.axes, t = a.axes^T * (b.center - a.center).
bool separated(const Vec3& ea, const Vec3& eb, const Mat3& r, const Vec3& t) {
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

}  // namespace

bool obb_overlap(const Obb& a, const Obb& b, Scalar margin) {
  const Mat3 r = a.axes.transpose() * b.axes;
  const Vec3 t = a.axes.transpose() * (b.center - a.center);
  return !separated(a.half_extents.array() + margin, b.half_extents, r, t);
}

bool obb_overlap(const Obb& a, const Obb& b, const Transform& b_to_a, Scalar margin) {
  const Mat3 r = a.axes.transpose() * (b_to_a.rotation * b.axes);
  const Vec3 t = a.axes.transpose() * (b_to_a.apply(b.center) - a.center);
  return !separated(a.half_extents.array() + margin, b.half_extents, r, t);
}

}  // namespace antcd::geometry
