// Private: lower bounds of the distance between the contents of two hierarchy nodes, used by the
// distance branch-and-bound to order and prune node pairs.
#pragma once

#include <antcd/bvh.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace antcd::detail {

/// Signed gap between two spheres: the distance between their surfaces when apart, minus the
/// depth of their overlap otherwise; `cb` is B's centre already in A's frame. Its positive part is
/// a lower bound of the distance between their contents; the signed value orders node pairs.
inline Scalar sphere_gap(const Sphere& a, const Vec3& cb, Scalar rb) {
  return (cb - a.center).norm() - a.radius - rb;
}

/// Largest gap between the two boxes' projections over 16 separating-axis candidates (the face
/// normals of each box, the line through their centres and the 9 cross products of their edges),
/// each axis normalised.
/// Projection onto a unit axis never lengthens a segment, so its positive part is a lower bound of
/// the distance between any point of `a` and any point of `b`. When no axis separates the boxes
/// the result is the (negative) largest face-axis gap: not a bound, a measure of overlap that
/// orders node pairs. B's box is given in A's frame (axes as columns, centre) with its half
/// extents `eb`. Returns as soon as the gap exceeds `stop` (the caller only needs to know that it
/// does).
inline Scalar obb_gap(const Obb& a, const Mat3& b_axes, const Vec3& b_center, const Vec3& eb,
                      Scalar stop) {
  const Mat3 r = a.axes.transpose() * b_axes;
  const Vec3 t = a.axes.transpose() * (b_center - a.center);
  const Vec3& ea = a.half_extents;
  const Mat3 abs_r = r.cwiseAbs();
  Scalar gap = -std::numeric_limits<Scalar>::infinity();
  for (int i = 0; i < 3; ++i) gap = std::max(gap, std::abs(t[i]) - ea[i] - abs_r.row(i).dot(eb));
  if (gap > stop) return gap;
  for (int j = 0; j < 3; ++j) {
    gap = std::max(gap, std::abs(t.dot(r.col(j))) - abs_r.col(j).dot(ea) - eb[j]);
  }
  if (gap > stop) return gap;
  // The axis through the two centres: it separates boxes side by side on a tilted line, which
  // no face axis and only some edge axis does.
  if (const Scalar len = t.norm(); len > 0) {
    const Vec3 u = t / len;
    gap = std::max(gap, len - u.cwiseAbs().dot(ea) - (r.transpose() * u).cwiseAbs().dot(eb));
    if (gap > stop) return gap;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      // Axis e_i × r_j (A's box coordinates), of squared length 1 - r(i, j)²; nearly parallel
      // edges give no useful axis and are skipped (a skipped axis only weakens the bound).
      const Scalar len2 = 1 - r(i, j) * r(i, j);
      if (!(len2 > 1e-12)) continue;
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const Scalar ra = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const Scalar rb = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      const Scalar d = std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) - ra - rb;
      if (d > 0 && (gap <= 0 || d * d > gap * gap * len2)) gap = d / std::sqrt(len2);
    }
  }
  return gap;
}

/// Lower bound of the distance between two axis-aligned boxes [lo_a, hi_a] and [lo_b, hi_b].
inline Scalar box_gap(const Vec3& lo_a, const Vec3& hi_a, const Vec3& lo_b, const Vec3& hi_b) {
  const Vec3 g = (lo_b - hi_a).cwiseMax(lo_a - hi_b).cwiseMax(Scalar{0});
  return g.norm();
}

/// Lower bound from a triangle's plane (through p0, unit normal n): when the three points `q` lie
/// strictly on one side of it, their smallest distance to it; else 0. (Rounded, so it may exceed
/// the exact value by a few ulps: not for deciding a touch.)
inline Scalar plane_gap(const Vec3& n, const Vec3& p0, const Vec3* q) {
  const Scalar d0 = n.dot(q[0] - p0);
  const Scalar d1 = n.dot(q[1] - p0);
  const Scalar d2 = n.dot(q[2] - p0);
  return std::max({Scalar{0}, std::min({d0, d1, d2}), -std::max({d0, d1, d2})});
}

/// Lower bound from the line through the two triangles' centroids `ca`, `cb`: the gap between
/// the projections of `p` (three points) and `q` onto the unit axis from ca to cb, or a negative
/// value when they overlap. It separates triangles that lie side by side, which the box and plane
/// gaps miss when the boxes are tilted. (Rounded like plane_gap.)
inline Scalar centroid_axis_gap(const Vec3& ca, const Vec3& cb, const Vec3* p, const Vec3* q) {
  const Vec3 d = cb - ca;
  const Scalar len = d.norm();
  if (!(len > 0)) return 0;
  const Vec3 u = d / len;
  const Scalar p_max = std::max({u.dot(p[0]), u.dot(p[1]), u.dot(p[2])});
  const Scalar q_min = std::min({u.dot(q[0]), u.dot(q[1]), u.dot(q[2])});
  return q_min - p_max;
}

}  // namespace antcd::detail
