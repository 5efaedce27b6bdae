// src/geometry/penetration.cpp — contact normal and penetration depth of two triangles by the
// separating-axis theorem (see antcd/geometry.hpp, triangle_penetration).
#include "geometry/penetration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace antcd::geometry {

namespace detail {

namespace {

struct Interval {
  Scalar lo;
  Scalar hi;
};

Interval project(const Vec3& axis, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Scalar x = axis.dot(p0), y = axis.dot(p1), z = axis.dot(p2);
  return {std::min({x, y, z}), std::max({x, y, z})};
}

// An edge pair's cross product counts as an axis when the edges are more than about 1e-6 rad from
// parallel: below that its direction is mostly rounding.
constexpr Scalar kMinSinSquared = 1e-12;

}  // namespace

TrianglePenetration intersecting_penetration(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                             const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const Vec3 ea[3] = {a1 - a0, a2 - a1, a0 - a2};
  const Vec3 eb[3] = {b1 - b0, b2 - b1, b0 - b2};
  const Vec3 na = ea[0].cross(-ea[2]);  // (a1 - a0) x (a2 - a0)
  const Vec3 nb = eb[0].cross(-eb[2]);
  // The preferred direction when both sides of an axis tie (rare: computed only then).
  const auto tie = [&] { return Vec3(nb.normalized() - na.normalized()); };

  TrianglePenetration best;
  best.depth = std::numeric_limits<Scalar>::infinity();
  const auto consider = [&](const Vec3& axis, Scalar norm) {
    const Interval ia = project(axis, a0, a1, a2);
    const Interval ib = project(axis, b0, b1, b2);
    // B moved by -s along the axis leaves it below A for s = ib.hi - ia.lo (A is then on the +axis
    // side, so the normal from B to A is +axis); moved by +s, s = ia.hi - ib.lo, normal -axis.
    const Scalar up = (ib.hi - ia.lo) / norm;
    const Scalar down = (ia.hi - ib.lo) / norm;
    const bool plus = up < down || (up == down && axis.dot(tie()) >= 0);
    const Scalar depth = plus ? up : down;
    if (depth < best.depth) {
      best.depth = depth;
      best.normal = (plus ? axis : Vec3(-axis)) / norm;
    }
  };
  const Scalar na_norm = na.norm();
  const Scalar nb_norm = nb.norm();
  if (na_norm > 0) consider(na, na_norm);
  if (nb_norm > 0) consider(nb, nb_norm);
  for (const Vec3& u : ea) {
    for (const Vec3& v : eb) {
      const Vec3 axis = u.cross(v);
      const Scalar n2 = axis.squaredNorm();
      if (n2 > kMinSinSquared * u.squaredNorm() * v.squaredNorm()) consider(axis, std::sqrt(n2));
    }
  }
  if (!(best.depth < std::numeric_limits<Scalar>::infinity())) {
    best = {};  // zero-area triangles (not supported): no axis at all
  }
  // The triangles intersect (exact predicate), so every axis overlaps: a negative value is the
  // rounding of a touching configuration.
  best.depth = std::max<Scalar>(best.depth, 0);
  return best;
}

TrianglePenetration apart_penetration(const Vec3& pa, const Vec3& pb) {
  const Vec3 d = pa - pb;
  const Scalar dist = d.norm();
  TrianglePenetration out;
  if (dist > 0) out.normal = d / dist;
  out.depth = -dist;
  return out;
}

}  // namespace detail

TrianglePenetration triangle_penetration(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                         const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const TriangleDistance td = triangle_distance(a0, a1, a2, b0, b1, b2);
  if (td.distance > 0) return detail::apart_penetration(td.pa, td.pb);
  return detail::intersecting_penetration(a0, a1, a2, b0, b1, b2);
}

}  // namespace antcd::geometry
