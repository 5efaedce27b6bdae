// src/geometry/distance.cpp — distances between points, segments and triangles, and the
// within-δ test (see antcd/geometry.hpp).
#include <antcd/geometry.hpp>
#include <antcd/tolerances.hpp>

#include "geometry/intersection.hpp"
#include "geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace antcd::geometry {

using namespace detail;

namespace {

Scalar point_segment_distance_squared(const Vec3& p, const Vec3& a, const Vec3& b, Vec3* closest) {
  const Vec3 d = b - a;
  const double dd = d.squaredNorm();
  double t = 0;
  if (dd > 0) t = std::clamp((p - a).dot(d) / dd, 0.0, 1.0);
  const Vec3 c = a + t * d;
  if (closest != nullptr) *closest = c;
  return (p - c).squaredNorm();
}

// The interior critical point of |p(s) - q(t)|² for p(s) = p0 + s (p1 - p0), q(t) = q0 + t (q1 -
// q0): when both parameters lie in [0, 1], its squared distance (x, y receive the points);
// otherwise, or for parallel segments, +inf. The other candidates of a segment pair's minimum have
// an end point of one segment, which callers cover separately.
Scalar segment_interior_distance_squared(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                         const Vec3& q1, Vec3& x, Vec3& y) {
  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = q1 - q0;
  const Vec3 r = p0 - q0;
  const Scalar a = d1.squaredNorm();
  const Scalar e = d2.squaredNorm();
  const Scalar b = d1.dot(d2);
  const Scalar denom = a * e - b * b;
  x = p0;
  y = q0;
  if (!(denom > 0)) return std::numeric_limits<Scalar>::infinity();
  const Scalar cc = d1.dot(r);
  const Scalar f = d2.dot(r);
  const Scalar s = (b * f - cc * e) / denom;
  const Scalar t = (a * f - b * cc) / denom;
  if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1)) return std::numeric_limits<Scalar>::infinity();
  x = p0 + s * d1;
  y = q0 + t * d2;
  return (x - y).squaredNorm();
}

// The squared distance of two disjoint triangles with a closest pair: the minimum is attained at
// a vertex of one and a point of the other (6 vertex-triangle distances) or at interior points of
// two edges (9 edge-pair critical points; an edge pair's end point cases are vertex-triangle ones).
Scalar disjoint_distance_squared(const Vec3* const A[3], const Vec3* const B[3], Vec3& pa,
                                 Vec3& pb) {
  Scalar best = std::numeric_limits<Scalar>::infinity();
  Vec3 c, cq;
  for (int i = 0; i < 3; ++i) {
    const Scalar d = point_triangle_distance_squared(*A[i], *B[0], *B[1], *B[2], &c);
    if (d < best) {
      best = d;
      pa = *A[i];
      pb = c;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const Scalar d = point_triangle_distance_squared(*B[i], *A[0], *A[1], *A[2], &c);
    if (d < best) {
      best = d;
      pa = c;
      pb = *B[i];
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Scalar d =
          segment_interior_distance_squared(*A[i], *A[(i + 1) % 3], *B[j], *B[(j + 1) % 3], c, cq);
      if (d < best) {
        best = d;
        pa = c;
        pb = cq;
      }
    }
  }
  return best;
}

}  // namespace

Scalar point_triangle_distance_squared(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                       Vec3* closest) {
  // The normal is taken at the vertex opposite the longest edge, whose angle is the largest: the
  // rounding error of a cross product relative to its length grows as 1 / sin(angle), so the
  // sharp tip of a needle is the worst place to take it. (b, c, a) and (c, a, b) keep the
  // orientation of (a, b, c).
  const Scalar lab = (b - a).squaredNorm();
  const Scalar lbc = (c - b).squaredNorm();
  const Scalar lca = (a - c).squaredNorm();
  const Vec3* o = &a;  // pivot: opposite the longest edge
  const Vec3* o1 = &b;
  const Vec3* o2 = &c;
  if (lca >= lab && lca >= lbc) {
    o = &b, o1 = &c, o2 = &a;
  } else if (lab >= lbc && lab >= lca) {
    o = &c, o1 = &a, o2 = &b;
  }
  const Vec3 n = (*o1 - *o).cross(*o2 - *o);
  const Scalar nn = n.squaredNorm();
  auto edges_only_into = [&](Vec3& best_c) {  // distance to the union of the three edges
    best_c = a;
    Vec3 cc;
    Scalar best = std::numeric_limits<Scalar>::infinity();
    const Vec3* v[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const Scalar d = point_segment_distance_squared(p, *v[i], *v[(i + 1) % 3], &cc);
      if (d < best) {
        best = d;
        best_c = cc;
      }
    }
    return best;
  };
  auto edges_only = [&]() {  // a zero-area triangle is the union of its edges
    Vec3 best_c;
    const Scalar best = edges_only_into(best_c);
    if (closest != nullptr) *closest = best_c;
    return best;
  };
  if (!(nn > 0)) return edges_only();
  // The closest point of the triangle to p is the closest one to q, p's projection onto the
  // plane. Voronoi regions of the triangle within its plane, told apart by the signs of the
  // (scaled) barycentric coordinates of q: all >= 0 -> face region, closest point q itself; one
  // negative -> the region of the opposite edge or of one of its end points; two negative -> the
  // region of their common vertex or of one of the two adjacent edges. The edge and vertex
  // regions are resolved by clamping onto the candidate edges. Everything is computed from
  // cross products of short vectors and point-segment projections, which stays accurate for
  // needle- and cap-shaped triangles (unlike closed-form barycentrics from dot products).
  const Vec3 q = p - (n.dot(p - *o) / nn) * n;
  const Vec3 qa = a - q, qb = b - q, qc = c - q;
  const Scalar wa = n.dot(qb.cross(qc));  // weight of a: side of q against edge bc
  const Scalar wb = n.dot(qc.cross(qa));  // weight of b: edge ca
  const Scalar wc = n.dot(qa.cross(qb));  // weight of c: edge ab
  if (wa >= 0 && wb >= 0 && wc >= 0) {
    const Scalar face = (p - q).squaredNorm();
    // A sliver (sine of its largest angle below 1e-3) has a plane that rounding tilts by up to
    // about 1e-16 / sine: its edges, which lie within the sliver's width of every point of it,
    // may then be nearer than the tilted projection says. Cheap triangles keep the fast path.
    const Scalar lmax = std::max({lab, lbc, lca});
    const Scalar lmid = lab + lbc + lca - lmax - std::min({lab, lbc, lca});
    if (nn < 1e-6 * lmax * lmid) {
      Vec3 edge_closest;
      const Scalar on_edges = edges_only_into(edge_closest);
      if (on_edges < face) {
        if (closest != nullptr) *closest = edge_closest;
        return on_edges;
      }
    }
    if (closest != nullptr) *closest = q;
    return face;
  }
  Vec3 best_c = a, cc;
  Scalar best = std::numeric_limits<Scalar>::infinity();
  auto edge = [&](Scalar w, const Vec3& e0, const Vec3& e1) {
    if (!(w < 0)) return;
    const Scalar d = point_segment_distance_squared(p, e0, e1, &cc);
    if (d < best) {
      best = d;
      best_c = cc;
    }
  };
  edge(wa, b, c);
  edge(wb, c, a);
  edge(wc, a, b);
  if (!(best < std::numeric_limits<Scalar>::infinity())) return edges_only();  // NaN input
  if (closest != nullptr) *closest = best_c;
  return best;
}

Scalar segment_segment_distance_squared(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                        const Vec3& q1, Vec3* cp, Vec3* cq) {
  // The minimum is attained either with both parameters interior (then at the unique critical
  // point of non-parallel segments) or with an end point of one segment; parallel segments
  // always have a minimising pair involving an end point. So the minimum over the four
  // end-point-to-segment distances and the interior critical point is exact.
  Vec3 bp = p0, bq = q0, c;
  Scalar best = std::numeric_limits<Scalar>::infinity();
  auto consider = [&](Scalar d, const Vec3& x, const Vec3& y) {
    if (d < best) {
      best = d;
      bp = x;
      bq = y;
    }
  };
  consider(point_segment_distance_squared(p0, q0, q1, &c), p0, c);
  consider(point_segment_distance_squared(p1, q0, q1, &c), p1, c);
  consider(point_segment_distance_squared(q0, p0, p1, &c), c, q0);
  consider(point_segment_distance_squared(q1, p0, p1, &c), c, q1);
  if (best > 0) {
    Vec3 x = p0, y = q0;
    const Scalar d = segment_interior_distance_squared(p0, p1, q0, q1, x, y);
    consider(d, x, y);
  }
  if (cp != nullptr) *cp = bp;
  if (cq != nullptr) *cq = bq;
  return best;
}

TriangleDistance triangle_distance(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                   const Vec3& b1, const Vec3& b2) {
  TriangleDistance out;
  Vec3 p;
  if (triangles_intersect(a0, a1, a2, b0, b1, b2, &p)) {
    out.distance = 0;
    out.pa = p;
    out.pb = p;
    return out;
  }
  const Vec3* A[3] = {&a0, &a1, &a2};
  const Vec3* B[3] = {&b0, &b1, &b2};
  out.distance = std::sqrt(disjoint_distance_squared(A, B, out.pa, out.pb));
  return out;
}

bool triangles_within(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                      const Vec3& b1, const Vec3& b2, Scalar delta, Vec3* point, Scalar* distance) {
  const Plane pa = make_plane(a0, a1, a2);
  SideValue vb[3] = {side_value(pa, b0), side_value(pa, b1), side_value(pa, b2)};

  if (!(delta > 0)) {  // delta == 0: exactly triangles_intersect
    if (certainly_one_side(vb)) return false;
    const Plane pb = make_plane(b0, b1, b2);
    SideValue va[3] = {side_value(pb, a0), side_value(pb, a1), side_value(pb, a2)};
    if (certainly_one_side(va)) return false;
    if (!intersect_core(pa, pb, va, vb, point)) return false;
    if (distance != nullptr) *distance = 0;
    return true;
  }

  // Conservative rejection: all vertices of one triangle farther than delta from the other's
  // plane, on one side. With D, N the exact n·(v - t0) and normal, |value - D| <= E (the orient3d
  // error bound) and |N| <= |fl(n)| + F, so value - E > delta * (|fl(n)| + F) proves D/|N| > delta.
  // The extra relative and coordinate-scale slack keeps the rejection consistent with the
  // rounding of the distance computed below.
  const Scalar scale =
      std::max({a0.cwiseAbs().maxCoeff(), a1.cwiseAbs().maxCoeff(), a2.cwiseAbs().maxCoeff(),
                b0.cwiseAbs().maxCoeff(), b1.cwiseAbs().maxCoeff(), b2.cwiseAbs().maxCoeff()});
  const Scalar slack = tolerance::widened(delta) + 1e-13 * scale;
  auto beyond_delta = [&](const Plane& pl, const SideValue(&sv)[3]) {
    const Scalar nlen = pl.n.norm();
    const Scalar reach = (nlen * (1 + 8 * kEps) + 8 * kEps * pl.nperm.sum()) * slack;
    bool pos = true, neg = true;
    for (const SideValue& s : sv) {
      const Scalar e = kOrient3dBound * s.perm;
      pos = pos && s.value - e > reach;
      neg = neg && s.value + e < -reach;
    }
    return pos || neg;
  };
  if (beyond_delta(pa, vb)) return false;
  const Plane pb = make_plane(b0, b1, b2);
  SideValue va[3] = {side_value(pb, a0), side_value(pb, a1), side_value(pb, a2)};
  if (beyond_delta(pb, va)) return false;

  if (intersect_core(pa, pb, va, vb, point)) {
    if (distance != nullptr) *distance = 0;
    return true;
  }
  const Vec3* A[3] = {&a0, &a1, &a2};
  const Vec3* B[3] = {&b0, &b1, &b2};
  Vec3 ca, cb;
  const Scalar d = std::sqrt(disjoint_distance_squared(A, B, ca, cb));
  if (!(d <= delta)) return false;
  if (point != nullptr) *point = (ca + cb) / 2;
  if (distance != nullptr) *distance = d;
  return true;
}

}  // namespace antcd::geometry
