// src/geometry/intersection.cpp — exact intersection of two closed triangles (see
// antcd/geometry.hpp; the predicates it decides by are in predicates.cpp).
//
// Intersection algorithm (closed triangles A and B)
// 1. Classify B's vertices against A's plane; all strictly on one side -> disjoint (the cheap
//    common path: one cross product, three dot products, no exact arithmetic unless a vertex is
//    within rounding distance of the plane). Same for A's vertices against B's plane.
//    When a vertex is within rounding distance of the other plane (near-coplanar pairs, where
//    the exact arithmetic would run), a floating-point certificate comes first: the projections
//    along the dominant axis of A's normal lie strictly apart across the line of an edge
//    (orient2d signs proved by their error bounds). Disjoint projections mean disjoint triangles.
// 2. Both triangles in one plane -> 2-D test after dropping the dominant axis of the normal:
//    they meet iff a vertex of one lies in the other or two edges meet.
// 3. Otherwise A∩B lies on the line where the planes meet, and it is empty or a segment whose
//    end points lie on the boundary of A or of B. So they meet iff an edge of one meets the
//    other (closed) triangle. An edge pq meets triangle abc iff p and q are not strictly on one
//    side of the plane and either (both on the plane) the segment meets the triangle in 2-D, or
//    orient3d(p,q,a,b), orient3d(p,q,b,c), orient3d(p,q,c,a) are all >= 0 or all <= 0.
#include <antcd/geometry.hpp>

#include "geometry/intersection.hpp"
#include "geometry/predicates.hpp"

#include <algorithm>
#include <cmath>

namespace antcd::geometry {
namespace detail {
namespace {

// Collinear p, a, b: is p inside the closed box of a and b (hence on the segment)?
bool within_box(const Vec3& p, const Vec3& a, const Vec3& b, const Projection& pr) {
  for (const int k : {pr.u, pr.v}) {
    if (p[k] < std::min(a[k], b[k]) || p[k] > std::max(a[k], b[k])) return false;
  }
  return true;
}

}  // namespace

// Closed segments [a,b] and [c,d] with all four points in one plane, tested in projection.
bool segments_meet_2d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                      const Projection& pr, Vec3* point) {
  const double o1 = orient2d(a, b, c, pr);
  const double o2 = orient2d(a, b, d, pr);
  if ((o1 > 0 && o2 > 0) || (o1 < 0 && o2 < 0)) return false;
  const double o3 = orient2d(c, d, a, pr);
  const double o4 = orient2d(c, d, b, pr);
  if ((o3 > 0 && o4 > 0) || (o3 < 0 && o4 < 0)) return false;
  if (o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0) {  // all on one line (or point segments)
    const Vec3* candidates[4][3] = {{&c, &a, &b}, {&d, &a, &b}, {&a, &c, &d}, {&b, &c, &d}};
    for (const auto& cand : candidates) {
      if (within_box(*cand[0], *cand[1], *cand[2], pr)) {
        if (point != nullptr) *point = *cand[0];
        return true;
      }
    }
    return false;
  }
  // The lines are distinct and the segments meet in one point.
  if (point != nullptr) {
    if (o1 == 0) {
      *point = c;
    } else if (o2 == 0) {
      *point = d;
    } else if (o3 == 0) {
      *point = a;
    } else if (o4 == 0) {
      *point = b;
    } else {
      // o3, o4 nonzero with opposite signs; their floating-point values may be off by up to their
      // error bound, so re-evaluate them accurately for the crossing point.
      const double a3 = orient2d(c, d, a, pr, kInterpolationMargin);
      const double a4 = orient2d(c, d, b, pr, kInterpolationMargin);
      const double t = std::clamp(a3 / (a3 - a4), 0.0, 1.0);
      *point = a + t * (b - a);
    }
  }
  return true;
}

namespace {

// Closed triangle abc (in projection) contains p; `o` = orient2d(a, b, c) must be nonzero.
bool contains_2d(const Vec3& a, const Vec3& b, const Vec3& c, double o, const Vec3& p,
                 const Projection& pr) {
  const int s = sign_of(o);
  return sign_of(orient2d(a, b, p, pr)) * s >= 0 && sign_of(orient2d(b, c, p, pr)) * s >= 0 &&
         sign_of(orient2d(c, a, p, pr)) * s >= 0;
}

// Closed segment pq against closed triangle T, all five points in one plane.
bool segment_meets_triangle_2d(const Vec3& p, const Vec3& q, const Vec3* const t[3],
                               const Projection& pr, Vec3* point) {
  const double o = orient2d(*t[0], *t[1], *t[2], pr);
  if (o != 0) {  // a zero-area T is the union of its edges: the edge tests below suffice
    for (const Vec3* e : {&p, &q}) {
      if (contains_2d(*t[0], *t[1], *t[2], o, *e, pr)) {
        if (point != nullptr) *point = *e;
        return true;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (segments_meet_2d(p, q, *t[i], *t[(i + 1) % 3], pr, point)) return true;
  }
  return false;
}

// Closed triangles A and B in one plane.
bool triangles_meet_2d(const Vec3* const A[3], const Vec3* const B[3], const Projection& pr,
                       Vec3* point) {
  const double oa = orient2d(*A[0], *A[1], *A[2], pr);
  const double ob = orient2d(*B[0], *B[1], *B[2], pr);
  if (ob != 0) {
    for (int i = 0; i < 3; ++i) {
      if (contains_2d(*B[0], *B[1], *B[2], ob, *A[i], pr)) {
        if (point != nullptr) *point = *A[i];
        return true;
      }
    }
  }
  if (oa != 0) {
    for (int i = 0; i < 3; ++i) {
      if (contains_2d(*A[0], *A[1], *A[2], oa, *B[i], pr)) {
        if (point != nullptr) *point = *B[i];
        return true;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (segments_meet_2d(*A[i], *A[(i + 1) % 3], *B[j], *B[(j + 1) % 3], pr, point)) return true;
    }
  }
  return false;
}

// Closed segment pq against the closed triangle of plane `pl` (non-degenerate), given the exact
// sides sp, sq of p, q and their plane values dp, dq (sign-exact).
bool edge_meets_triangle(const Vec3& p, const Vec3& q, int sp, int sq, const SideValue& dp,
                         const SideValue& dq, const Plane& pl, Vec3* point) {
  if (sp * sq > 0) return false;
  const Vec3& a = *pl.t[0];
  const Vec3& b = *pl.t[1];
  const Vec3& c = *pl.t[2];
  if (sp == 0 && sq == 0) {
    return segment_meets_triangle_2d(p, q, pl.t, Projection(dominant_axis(pl.n)), point);
  }
  // The line pq crosses the plane in one point, which lies on the segment. The signs of
  // orient3d(p, q, a, b), (p, q, b, c), (p, q, c, a), all three negated (which the test below does
  // not see): orient3d(p, q, x, y) = -orient3d(q, x, y, p), so the differences to p are shared.
  const Vec3 e = q - p, wa = a - p, wb = b - p, wc = c - p;
  const int s1 = sign_of(orient3d_with_differences(q, a, b, p, e, wa, wb));
  const int s2 = sign_of(orient3d_with_differences(q, b, c, p, e, wb, wc));
  const int s3 = sign_of(orient3d_with_differences(q, c, a, p, e, wc, wa));
  const bool hit = (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
  if (hit && point != nullptr) {
    if (sp == 0) {
      *point = p;
    } else if (sq == 0) {
      *point = q;
    } else {
      // dp, dq nonzero with opposite signs.
      const double vp = accurate_side(pl, p, dp);
      const double vq = accurate_side(pl, q, dq);
      const double t = std::clamp(vp / (vp - vq), 0.0, 1.0);
      *point = p + t * (q - p);
    }
  }
  return hit;
}

// Every value's sign proved by its error bound.
bool all_certain(const SideValue (&sv)[3]) {
  for (const SideValue& s : sv) {
    const double bound = kOrient3dBound * s.perm;
    if (!(s.value > bound || -s.value > bound)) return false;
  }
  return true;
}

// The projections of the triangles of `pa` and `pb` along the dominant axis of pa's normal are
// proved disjoint: for an edge of one whose third corner has a proved nonzero orientation, the
// other's three corners are proved strictly on the other side of the edge's line (floating-point
// signs only; false: not proved). Triangles with disjoint projections are disjoint.
bool apart_in_projection(const Plane& pa, const Plane& pb) {
  const Projection pr(dominant_axis(pa.n));
  const Vec3* const* tri[2] = {pa.t, pb.t};
  for (int s = 0; s < 2; ++s) {
    const Vec3* const* t = tri[s];
    const Vec3* const* o = tri[1 - s];
    const int own = orient2d_sign_if_certain(*t[0], *t[1], *t[2], pr);
    if (own == 0) continue;
    for (int i = 0; i < 3; ++i) {
      const Vec3& p = *t[i];
      const Vec3& q = *t[(i + 1) % 3];
      if (orient2d_sign_if_certain(p, q, *o[0], pr) == -own &&
          orient2d_sign_if_certain(p, q, *o[1], pr) == -own &&
          orient2d_sign_if_certain(p, q, *o[2], pr) == -own) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

// Everything after the cheap plane rejection: `va`/`vb` are the plane values of A's vertices
// against B's plane and of B's vertices against A's plane.
bool intersect_core(const Plane& pa, const Plane& pb, SideValue (&va)[3], SideValue (&vb)[3],
                    Vec3* point) {
  int sb[3];
  for (int i = 0; i < 3; ++i) sb[i] = side_sign(pa, *pb.t[i], vb[i]);
  if (strictly_one_side(sb)) return false;
  int sa[3];
  for (int i = 0; i < 3; ++i) sa[i] = side_sign(pb, *pa.t[i], va[i]);
  if (strictly_one_side(sa)) return false;

  const bool a_in_b_plane = all_zero(sa);
  const bool b_in_a_plane = all_zero(sb);
  if (a_in_b_plane && b_in_a_plane) {
    // Coplanar (for non-degenerate input both hold together). Project along the better normal.
    const Vec3& n = pa.n.cwiseAbs().maxCoeff() >= pb.n.cwiseAbs().maxCoeff() ? pa.n : pb.n;
    if (n.cwiseAbs().maxCoeff() == 0) {
      // Both triangles degenerate (unsupported input): compare their edges.
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          Vec3 cp, cq;
          if (segment_segment_distance_squared(*pa.t[i], *pa.t[(i + 1) % 3], *pb.t[j],
                                               *pb.t[(j + 1) % 3], &cp, &cq) == 0) {
            if (point != nullptr) *point = cp;
            return true;
          }
        }
      }
      return false;
    }
    return triangles_meet_2d(pa.t, pb.t, Projection(dominant_axis(n)), point);
  }
  // Not coplanar. An all-zero side pattern only happens when the OTHER triangle is degenerate;
  // a degenerate triangle is the union of its edges, so testing its edges alone is exact.
  if (!a_in_b_plane) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (edge_meets_triangle(*pa.t[i], *pa.t[j], sa[i], sa[j], va[i], va[j], pb, point)) {
        return true;
      }
    }
  }
  if (!b_in_a_plane) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (edge_meets_triangle(*pb.t[i], *pb.t[j], sb[i], sb[j], vb[i], vb[j], pa, point)) {
        return true;
      }
    }
  }
  return false;
}

bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c) {
  const Plane pl = make_plane(a, b, c);
  SideValue dp = side_value(pl, p);
  SideValue dq = side_value(pl, q);
  const int sp = side_sign(pl, p, dp);
  const int sq = side_sign(pl, q, dq);
  return edge_meets_triangle(p, q, sp, sq, dp, dq, pl, nullptr);
}

}  // namespace detail

using namespace detail;

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                         const Vec3& b1, const Vec3& b2, Vec3* point) {
  const Plane pa = make_plane(a0, a1, a2);
  SideValue vb[3] = {side_value(pa, b0), side_value(pa, b1), side_value(pa, b2)};
  if (certainly_one_side(vb)) return false;  // the common, cheap rejection
  const Plane pb = make_plane(b0, b1, b2);
  SideValue va[3] = {side_value(pb, a0), side_value(pb, a1), side_value(pb, a2)};
  if (certainly_one_side(va)) return false;
  if (!(all_certain(va) && all_certain(vb)) && apart_in_projection(pa, pb)) return false;
  return intersect_core(pa, pb, va, vb, point);
}

}  // namespace antcd::geometry
